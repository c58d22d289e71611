// Butterworth low-pass designed at run time.
#include <legwork/core/types.hpp>
#include <legwork/wip/filter.hpp>

#include <gtest/gtest.h>

#include <cmath>

namespace legwork::wip {
namespace {

double db(double x) { return 20 * std::log10(x); }

TEST(Butterworth, MinusThreeDbAtCutoffForCommonRates) {
  for (double rate : {30.0, 60.0, 90.0, 120.0})
    for (int order : {1, 2, 3, 4}) {
      Butterworth f(order, 4.0, rate);
      EXPECT_NEAR(db(f.magnitude(4.0)), -3.0103, 0.1) << rate << " Hz, order " << order;
      EXPECT_NEAR(f.magnitude(0.0), 1.0, 1e-12);
      EXPECT_LT(f.magnitude(8.0), f.magnitude(4.0));
    }
}

TEST(Butterworth, SimulatedSineAtCutoffIsAttenuatedByThreeDb) {
  const double rate = 30.0, fc = 4.0;
  Butterworth f(2, fc, rate);
  double peak = 0;
  for (int i = 0; i < 30 * 20; ++i) {
    const double y = f.step(std::sin(2 * kPi * fc * i / rate));
    if (i > 30 * 10) peak = std::max(peak, std::abs(y));
  }
  // Sampled at 30 Hz the peak can fall between samples: allow a little.
  EXPECT_NEAR(db(peak), -3.01, 0.25);
}

TEST(Butterworth, StepResponseSettlesWithSmallOvershoot) {
  Butterworth f(2, 4.0, 30.0);
  f.reset(0.0);
  double y = 0, peak = 0;
  for (int i = 0; i < 30; ++i) {
    y = f.step(1.0);
    peak = std::max(peak, y);
  }
  EXPECT_NEAR(y, 1.0, 1e-3);       // settled after 1 s
  EXPECT_LT(peak, 1.06);           // second-order Butterworth overshoots ~4 %
  EXPECT_GT(peak, 1.0);
}

TEST(Butterworth, NanInputHoldsAndPrimingAvoidsTransient) {
  Butterworth f(2, 4.0, 30.0);
  EXPECT_DOUBLE_EQ(f.step(0.8), 0.8);  // primed at the first value
  for (int i = 0; i < 10; ++i) EXPECT_NEAR(f.step(0.8), 0.8, 1e-12);
  for (int i = 0; i < 10; ++i) {
    const double y = f.step(std::nan(""));
    EXPECT_TRUE(std::isfinite(y));
    EXPECT_NEAR(y, 0.8, 1e-9);
  }
  EXPECT_TRUE(std::isfinite(f.step(INFINITY)));
}

}  // namespace
}  // namespace legwork::wip
