#include "trigger.hpp"

#include <cmath>

namespace tetray {

void TriggerClock::mark_rendered(double time) {
  rendered_ = true;
  if (trigger_.every_time <= 0) return;
  const double period = trigger_.every_time;
  const double tolerance = 1e-9;
  next_time_ = (std::floor(time / period + tolerance) + 1) * period - tolerance * period;
}

}  // namespace tetray
