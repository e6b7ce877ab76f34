#include "adaptor/step/trigger.hpp"

#include <cmath>
#include <limits>

namespace tetray {

bool TriggerClock::due(std::int64_t step, double time) const {
  if (trigger_.every_time > 0) return std::isfinite(time) && (!rendered_ || time >= next_time_);
  const std::int64_t n = trigger_.every_steps;
  return ((step % n) + n) % n == 0;
}

void TriggerClock::mark_rendered(double time) {
  rendered_ = true;
  if (trigger_.every_time <= 0 || !std::isfinite(time)) return;
  const double period = trigger_.every_time;
  const double tolerance = 1e-9;
  next_time_ = (std::floor(time / period + tolerance) + 1) * period - tolerance * period;
  // A period below the resolution of `time` (time / period overflows, or adding one period
  // is lost in rounding) renders at every later time, never at none.
  if (!(next_time_ > time) || !std::isfinite(next_time_))
    next_time_ = std::nextafter(time, std::numeric_limits<double>::infinity());
}

}  // namespace tetray
