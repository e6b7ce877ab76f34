// The clock that cuts an execute call into the log's phases (adaptor/step/phase_clock.hpp): every
// instant goes to exactly one column, so the columns sum to the total; a nested phase takes its
// own time from the outer one; time outside every phase goes to the remainder. Sleeps give each
// phase a known least duration (sleep_for never returns early); no upper bound is checked.
#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "adaptor/step/phase_clock.hpp"

namespace tetray {
namespace {

using std::chrono::milliseconds;

void sleep_ms(int ms) { std::this_thread::sleep_for(milliseconds(ms)); }

TEST(PhaseClock, ColumnsSumToTheTotalAndNestedPhasesChargeTheInnerColumn) {
  double remainder = 0, outer = 0, inner = 0;
  PhaseClock clock;
  clock.start(&remainder);
  sleep_ms(5);
  {
    const PhaseClock::Phase a(clock, outer);
    sleep_ms(10);
    {
      const PhaseClock::Phase b(clock, inner);
      sleep_ms(20);
    }
    sleep_ms(10);
  }
  sleep_ms(5);
  const double total = clock.stop();
  EXPECT_GE(remainder, 10.0);
  EXPECT_GE(outer, 20.0);
  EXPECT_GE(inner, 20.0);
  EXPECT_GE(total, 50.0);
  // Each column is a sum of the clock's own intervals: only the doubles' rounding apart.
  EXPECT_NEAR(remainder + outer + inner, total, 1e-9 * total);
}

TEST(PhaseClock, APhaseAddsToItsColumnAndStopEndsTheCharging) {
  double remainder = 0, column = 7;
  PhaseClock clock;
  clock.start(&remainder);
  {
    const PhaseClock::Phase a(clock, column);
    sleep_ms(5);
  }
  {
    const PhaseClock::Phase again(clock, column);
    sleep_ms(5);
  }
  const double total = clock.stop();
  EXPECT_GE(column, 7.0 + 10.0);
  EXPECT_NEAR(remainder + (column - 7), total, 1e-9 * total);
  const double after_stop = remainder;
  sleep_ms(2);
  {
    const PhaseClock::Phase late(clock, column);  // outside a call: the remainder is not charged
  }
  EXPECT_EQ(remainder, after_stop);
}

}  // namespace
}  // namespace tetray
