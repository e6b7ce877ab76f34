// When a scene renders: every N steps, or each time the simulated time reaches the next
// multiple of T. Checked on every execute call, so it does no allocation and no MPI.
#pragma once

#include <cstdint>

#include "adaptor/config/config.hpp"

namespace tetray {

class TriggerClock {
 public:
  explicit TriggerClock(const config::Trigger& trigger) : trigger_(trigger) {}

  // A time trigger is never due at a NaN or infinite time (the step renders no scene of that
  // trigger, and the schedule is unchanged); a step trigger ignores the time.
  bool due(std::int64_t step, double time) const;

  // After a render at `time`, the next time trigger is the next multiple of T strictly after
  // it. The small tolerance keeps times like 0.1 * 3 (= 0.30000000000000004) on schedule. A
  // period too small to step from `time` (T below its rounding) makes every later time due.
  void mark_rendered(double time);

 private:
  config::Trigger trigger_;
  bool rendered_ = false;
  double next_time_ = 0;
};

}  // namespace tetray
