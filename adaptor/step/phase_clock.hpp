// One clock for a whole execute call, cut into contiguous phases, so that the stage columns of
// tetray_log.csv sum to the call's blocked time by construction (docs/outputs.md, "The timing
// log"). Every moment from start() to stop() is charged to exactly one column: that of the
// innermost Phase open at that moment, or, outside every phase, the remainder column start()
// was given. Separate stopwatches per stage would leave the moments between them in no column,
// and a stage measured inside another in two.
#pragma once

#include <chrono>

namespace tetray {

class PhaseClock {
 public:
  using Clock = std::chrono::steady_clock;

  // Starts the call: from now on time goes to `remainder` (milliseconds, added to) until a phase
  // opens.
  void start(double* remainder) {
    start_ = last_ = Clock::now();
    column_ = remainder;
  }

  // Ends the call: the time since the last change of column goes to that column, and the time
  // since start() comes back (ms). No column is charged after this until the next start().
  double stop() {
    charge(Clock::now());
    column_ = nullptr;
    return ms(last_ - start_);
  }

  // Time from here to the end of the scope goes to `column` (ms, added to); the time before it
  // to the column that was open. Nested phases charge the inner one; the outer resumes after.
  class Phase {
   public:
    Phase(PhaseClock& clock, double& column) : clock_(clock), outer_(clock.switch_to(&column)) {}
    ~Phase() { clock_.switch_to(outer_); }
    Phase(const Phase&) = delete;
    Phase& operator=(const Phase&) = delete;

   private:
    PhaseClock& clock_;
    double* outer_;
  };

 private:
  static double ms(Clock::duration d) {
    return std::chrono::duration<double, std::milli>(d).count();
  }

  void charge(Clock::time_point now) {
    if (column_ != nullptr) *column_ += ms(now - last_);
    last_ = now;
  }

  // Charges the open column up to now and opens `column`; returns the one that was open.
  double* switch_to(double* column) {
    charge(Clock::now());
    double* was = column_;
    column_ = column;
    return was;
  }

  Clock::time_point start_{}, last_{};
  double* column_ = nullptr;
};

}  // namespace tetray
