// Tick values for a color range: "nice" numbers (1, 2 or 5 times a power of ten) after
// Heckbert 1990, "Nice numbers for graph labels" (Graphics Gems I), but with the ticks kept
// inside the range rather than the range widened to the ticks, since a colorbar shows exactly
// the colors the surfaces use.
#pragma once

#include <string>
#include <vector>

namespace tetray::render {

struct Ticks {
  std::vector<double> values;  // ascending, within [lo, hi]
  double step = 0;             // spacing of the values: 1, 2 or 5 x 10^k
};

inline constexpr int kMinTicks = 3;
inline constexpr int kMaxTicks = 7;

// Between kMinTicks and kMaxTicks multiples of one nice step inside [lo, hi], as close to 5 as
// the range allows; needs lo < hi, both finite.
Ticks nice_ticks(double lo, double hi);

// A tick value with as many decimals as the step needs ("0.25", "-3", "1.5e+06" for steps
// beyond 1e5 or below 1e-4).
std::string tick_label(double value, double step);

}  // namespace tetray::render
