#include "nice_ticks.hpp"

#include <cmath>
#include <cstdio>

namespace tetray::render {
namespace {

// The multiples of `step` in [lo, hi]. Rounding is forgiven by a millionth of a step, so that a
// range ending on a multiple (0..1 with step 0.2) keeps its end ticks.
std::vector<double> multiples_within(double lo, double hi, double step) {
  const double slack = 1e-6;
  const double first = std::ceil(lo / step - slack);
  const double last = std::floor(hi / step + slack);
  std::vector<double> values;
  for (double k = first; k <= last && values.size() <= kMaxTicks; ++k) {
    const double v = k * step;
    values.push_back(v == 0 ? 0.0 : v);  // no "-0"
  }
  return values;
}

}  // namespace

Ticks nice_ticks(double lo, double hi) {
  Ticks best;
  double best_distance = 1e300;
  const double magnitude = std::floor(std::log10(hi - lo));
  // From steps near a tenth of the range to steps near the range itself.
  for (double exponent = magnitude - 2; exponent <= magnitude; ++exponent) {
    for (double mantissa : {1.0, 2.0, 5.0}) {
      const double step = mantissa * std::pow(10.0, exponent);
      std::vector<double> values = multiples_within(lo, hi, step);
      const auto count = static_cast<int>(values.size());
      if (count < kMinTicks || count > kMaxTicks) continue;
      const double distance = std::abs(count - 5.0);
      if (distance < best_distance) {
        best = {std::move(values), step};
        best_distance = distance;
      }
    }
  }
  // Unreachable for finite lo < hi (some step of 1, 2, 5 x 10^k always fits 3 to 7 times), kept
  // so that a range lost to rounding still gets its ends.
  if (best.values.empty()) best = {{lo, hi}, hi - lo};
  return best;
}

std::string tick_label(double value, double step) {
  char text[64];
  if (step >= 1e5 || step < 1e-4) {
    std::snprintf(text, sizeof text, "%.3g", value);
    return text;
  }
  const int decimals = std::max(0, static_cast<int>(-std::floor(std::log10(step) + 1e-9)));
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

}  // namespace tetray::render
