// When a scene renders: every N steps, or each time the simulated time reaches the next
// multiple of T. Checked on every execute call, so it does no allocation and no MPI.
#pragma once

#include <cstdint>

#include "config.hpp"

namespace tetray {

class TriggerClock {
 public:
  explicit TriggerClock(const config::Trigger& trigger) : trigger_(trigger) {}

  bool due(std::int64_t step, double time) const {
    if (trigger_.every_time > 0) return !rendered_ || time >= next_time_;
    const std::int64_t n = trigger_.every_steps;
    return ((step % n) + n) % n == 0;
  }

  // After a render at `time`, the next time trigger is the next multiple of T strictly after
  // it. The small tolerance keeps times like 0.1 * 3 (= 0.30000000000000004) on schedule.
  void mark_rendered(double time);

 private:
  config::Trigger trigger_;
  bool rendered_ = false;
  double next_time_ = 0;
};

}  // namespace tetray
