#pragma once
// Statistics of series of numbers, one definition each for every module:
// mean and sample standard deviation, median, percentile and Pearson
// correlation. Offline helpers (median and percentile copy their input).
#include <limits>
#include <span>
#include <vector>

namespace legwork {

// A quiet NaN: what a statistic of too few (or no) numbers is.
inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Mean and sample standard deviation (n - 1) of the finite values; mean NaN
// when there is none, sd 0 with fewer than two.
struct MeanSd {
  double mean = 0;
  double sd = 0;
  int n = 0;  // finite values counted
};
MeanSd mean_sd(std::span<const double> values);

// The upper median: the value at index n/2 of the sorted values; 0 if empty.
double median(std::vector<double> values);

// Nearest-rank percentile: the value at index floor(p * (n - 1)) of the
// sorted values, p clamped to [0, 1]; 0 if empty.
double percentile(std::vector<double> values, double p);

// Pearson correlation of the first min(|a|, |b|) pairs, clamped to [-1, 1];
// NaN with fewer than two pairs or when either series does not move (spread
// below 1e-12 per sample, i.e. about a micrometre).
double pearson(std::span<const double> a, std::span<const double> b);

}  // namespace legwork
