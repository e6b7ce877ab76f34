// Ticks checked against their definition over ranges of every magnitude and sign: 3 to 7 values,
// all inside the range, evenly spaced by 1, 2 or 5 times a power of ten, each a multiple of it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "render/annotate/nice_ticks.hpp"

namespace tetray::render {
namespace {

// Whether `step` is 1, 2 or 5 times a power of ten.
bool is_nice(double step) {
  const double mantissa = step / std::pow(10.0, std::floor(std::log10(step) + 1e-9));
  for (double m : {1.0, 2.0, 5.0}) {
    if (std::abs(mantissa - m) < 1e-9 * m) return true;
  }
  return false;
}

void expect_valid(double lo, double hi) {
  SCOPED_TRACE("range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
  const Ticks ticks = nice_ticks(lo, hi);
  const auto n = static_cast<int>(ticks.values.size());
  EXPECT_GE(n, kMinTicks);
  EXPECT_LE(n, kMaxTicks);
  EXPECT_TRUE(is_nice(ticks.step)) << ticks.step;
  const double slack = 1e-6 * ticks.step;
  for (int k = 0; k < n; ++k) {
    const double v = ticks.values[k];
    EXPECT_GE(v, lo - slack);
    EXPECT_LE(v, hi + slack);
    const double multiple = v / ticks.step;
    EXPECT_NEAR(multiple, std::round(multiple), 1e-6) << v;
    if (k > 0) {
      EXPECT_NEAR(v - ticks.values[k - 1], ticks.step, slack);
    }
  }
}

TEST(NiceTicks, UnitRangeGetsFifths) {
  const Ticks ticks = nice_ticks(0, 1);
  ASSERT_EQ(ticks.values.size(), 6u);
  EXPECT_DOUBLE_EQ(ticks.step, 0.2);
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(ticks.values[k], 0.2 * k, 1e-12);
}

TEST(NiceTicks, KeepsInsideAnOddRange) {
  const Ticks ticks = nice_ticks(-3.7, 12.1);  // step 5 would give 3: 0, 5, 10; 2 gives 8
  EXPECT_DOUBLE_EQ(ticks.step, 5);
  EXPECT_EQ(ticks.values, (std::vector<double>{0, 5, 10}));
  expect_valid(-3.7, 12.1);
}

TEST(NiceTicks, EveryMagnitudeAndSign) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> exponent(-12, 12), unit(-1, 1), width(0.01, 1);
  for (int trial = 0; trial < 5000; ++trial) {
    const double scale = std::pow(10.0, exponent(rng));
    const double lo = scale * unit(rng);
    expect_valid(lo, lo + scale * width(rng));
  }
  expect_valid(0, 14);  // 8 multiples of 2, 3 of 5
  expect_valid(1e6, 1e6 + 0.5);
  expect_valid(-1, 0);
}

TEST(NiceTicks, LabelsShowTheDecimalsTheStepNeeds) {
  EXPECT_EQ(tick_label(0.2 * 3, 0.2), "0.6");
  EXPECT_EQ(tick_label(0.25, 0.05), "0.25");
  EXPECT_EQ(tick_label(1500, 500), "1500");
  EXPECT_EQ(tick_label(-0.004, 0.002), "-0.004");
  EXPECT_EQ(tick_label(2e7, 1e7), "2e+07");
  EXPECT_EQ(tick_label(3e-6, 1e-6), "3e-06");
}

}  // namespace
}  // namespace tetray::render
