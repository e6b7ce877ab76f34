// Wall-clock milliseconds since construction: the stage times of the timing log and of the
// benchmarks all come from this one clock.
#pragma once

#include <chrono>

namespace tetray::render {

class Stopwatch {
 public:
  double ms() const {
    return std::chrono::duration<double, std::milli>(Clock::now() - start_).count();
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point start_ = Clock::now();
};

}  // namespace tetray::render
