// Rolling minimum (src/core/series.cpp) against a brute-force window scan, on
// a real ankle-height track.
#include <legwork/core/fk.hpp>
#include <legwork/core/series.hpp>

#include "cmu_sample.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

using namespace legwork;

namespace {
std::vector<double> brute_rolling_min(const std::vector<double>& x, int w) {
  const int n = static_cast<int>(x.size());
  std::vector<double> out(x.size());
  for (int i = 0; i < n; ++i)
    out[static_cast<std::size_t>(i)] =
        *std::min_element(x.begin() + std::max(0, i - w), x.begin() + std::min(n, i + w + 1));
  return out;
}

std::vector<double> left_ankle_heights() {
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const auto p = joint_positions(m);
  const auto n = static_cast<std::size_t>(m.joint_count());
  const auto a = static_cast<std::size_t>(m.skeleton.roles[Role::LeftAnkle]);
  std::vector<double> y;
  for (int f = 0; f < m.frame_count(); ++f) y.push_back(p[static_cast<std::size_t>(f) * n + a].y());
  return y;
}
}  // namespace

TEST(RollingMin, EqualsTheWindowMinimumOnARealAnkleTrack) {
  const auto y = left_ankle_heights();
  ASSERT_GT(y.size(), 100u);
  for (int w : {0, 1, 5, 60, static_cast<int>(y.size())}) EXPECT_EQ(rolling_min(y, w), brute_rolling_min(y, w)) << "w=" << w;
  // A window wider than the track sees everything: the global minimum.
  const auto all = rolling_min(y, static_cast<int>(y.size()));
  EXPECT_EQ(all.front(), *std::min_element(y.begin(), y.end()));
  EXPECT_EQ(rolling_min(y, 0), y);
}

TEST(RollingMin, HandlesTiesPlateausAndShortInputs) {
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> level(0, 4);  // few levels: many ties
  for (int n : {1, 2, 3, 17, 200}) {
    std::vector<double> x(static_cast<std::size_t>(n));
    for (auto& v : x) v = level(rng);
    for (int w : {0, 1, 2, 7, 300}) EXPECT_EQ(rolling_min(x, w), brute_rolling_min(x, w)) << "n=" << n << " w=" << w;
  }
  EXPECT_TRUE(rolling_min({}, 3).empty());
}

TEST(RollingMin, NegativeWindowIsAnError) {
  try {
    (void)rolling_min({1.0, 2.0}, -1);
    ADD_FAILURE() << "expected an error";
  } catch (const Error& e) {
    EXPECT_STREQ(e.what(), "rolling_min: window must be >= 0 samples, got -1");
  }
}
