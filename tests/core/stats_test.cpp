// Statistics helpers: known values by hand and on a real CMU walk.
#include <legwork/core/fk.hpp>
#include <legwork/core/stats.hpp>

#include <gtest/gtest.h>

#include <cmath>

#include "cmu_sample.hpp"
#include "testdata.hpp"

using namespace legwork;

TEST(Stats, PearsonKnownValues) {
  const std::vector<double> x{1, 2, 3, 4, 5};
  const std::vector<double> up{3, 5, 7, 9, 11}, down{5, 4, 3, 2, 1}, flat{2, 2, 2, 2, 2};
  EXPECT_NEAR(pearson(x, up), 1.0, 1e-12);
  EXPECT_NEAR(pearson(x, down), -1.0, 1e-12);
  EXPECT_TRUE(std::isnan(pearson(x, flat)));
  EXPECT_TRUE(std::isnan(pearson(std::vector<double>{1.0}, std::vector<double>{2.0})));
  const std::vector<double> y{1, 3, 2, 5, 4};  // r = 0.8 by hand: sxy = 8, sxx = syy = 10
  EXPECT_NEAR(pearson(x, y), 0.8, 1e-12);
}

TEST(Stats, MeanAndSampleSdSkipNonFinite) {
  const std::vector<double> v{1, 2, 3, std::nan("")};
  const MeanSd s = mean_sd(v);
  EXPECT_EQ(s.n, 3);
  EXPECT_NEAR(s.mean, 2.0, 1e-12);
  EXPECT_NEAR(s.sd, 1.0, 1e-12);
  EXPECT_TRUE(std::isnan(mean_sd(std::vector<double>{}).mean));
  EXPECT_EQ(mean_sd(std::vector<double>{4.0}).sd, 0.0);
}

TEST(Stats, MedianAndPercentileByRank) {
  EXPECT_EQ(median({5, 1, 4, 2, 3}), 3.0);
  EXPECT_EQ(median({4, 1, 3, 2}), 3.0);  // upper median: index n/2 of the sorted values
  EXPECT_EQ(median({}), 0.0);
  const std::vector<double> v{50, 10, 40, 20, 30};
  EXPECT_EQ(percentile(v, 0.0), 10.0);
  EXPECT_EQ(percentile(v, 0.5), 30.0);
  EXPECT_EQ(percentile(v, 0.74), 30.0);  // floor(0.74 * 4) = 2
  EXPECT_EQ(percentile(v, 0.75), 40.0);
  EXPECT_EQ(percentile(v, 2.0), 50.0);  // clamped
  EXPECT_EQ(percentile({}, 0.5), 0.0);
}

TEST(Stats, AnkleHeightsOfARealWalk) {
  // 07_01: the left ankle rests near its floor level most of the time and
  // lifts in swing, so its 5th percentile is below its median, which is below
  // its 95th; left and right ankle heights are not identical series.
  const Motion m = testdata::load_sample("cmu/bvh/walking/07_01.bvh");
  const auto pos = joint_positions(m);
  const auto nj = static_cast<std::size_t>(m.joint_count());
  std::vector<double> left, right;
  for (int f = 0; f < m.frame_count(); ++f) {
    left.push_back(pos[static_cast<std::size_t>(f) * nj + static_cast<std::size_t>(m.skeleton.roles[Role::LeftAnkle])].y());
    right.push_back(pos[static_cast<std::size_t>(f) * nj + static_cast<std::size_t>(m.skeleton.roles[Role::RightAnkle])].y());
  }
  const double low = percentile(left, 0.05), mid = median(left), high = percentile(left, 0.95);
  EXPECT_LT(low, mid);
  EXPECT_LT(mid, high);
  EXPECT_GT(high - low, 0.05);  // a walking ankle lifts by more than 5 cm
  const MeanSd s = mean_sd(left);
  EXPECT_EQ(s.n, m.frame_count());
  EXPECT_GT(s.mean, low);
  EXPECT_LT(s.mean, high);
  // In a walk one foot lifts while the other stands: the two heights are not
  // positively locked together.
  EXPECT_LT(pearson(left, right), 0.5);
}
