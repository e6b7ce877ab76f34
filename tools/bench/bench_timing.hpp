// Wall-clock timing for the benchmark. Every figure is the best of a few repetitions after a
// warm-up: on a shared machine the minimum is the least disturbed estimate of the cost, and the
// same rule applies to tetray and to the references so their ratios stay fair.
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <limits>

#include "render/core/stopwatch.hpp"

namespace tetray::bench {

inline constexpr int kRepetitions = 3;

template <typename Work>
double time_ms(Work&& work) {
  const render::Stopwatch watch;
  work();
  return watch.ms();
}

// Best of `repetitions` runs of `measure`, which times (a part of) its own work and returns ms.
template <typename Measure>
double best_of_ms(int repetitions, Measure&& measure) {
  double best = std::numeric_limits<double>::infinity();
  for (int r = 0; r < repetitions; ++r) best = std::min(best, measure());
  return best;
}

// Best of `repetitions` timed runs of `work`; `prepare` runs untimed before each (e.g. to
// restore an input that `work` consumes).
template <typename Prepare, typename Work>
double best_ms(int repetitions, Prepare&& prepare, Work&& work) {
  return best_of_ms(repetitions, [&] {
    prepare();
    return time_ms(work);
  });
}

template <typename Work>
double best_ms(int repetitions, Work&& work) {
  return best_ms(
      repetitions, [] {}, work);
}

// The best of `repetitions` runs of each measure (as in best_of_ms), the measures run in turn so
// that they share the conditions of a shared machine, in an order that rotates from repetition
// to repetition so that none always follows the same one (and finds its caches).
template <std::size_t N>
std::array<double, N> best_in_turn_ms(int repetitions,
                                      const std::array<std::function<double()>, N>& measures) {
  std::array<double, N> best;
  best.fill(std::numeric_limits<double>::infinity());
  for (int r = 0; r < repetitions; ++r)
    for (std::size_t k = 0; k < N; ++k) {
      const std::size_t m = (k + static_cast<std::size_t>(r)) % N;
      best[m] = std::min(best[m], measures[m]());
    }
  return best;
}

}  // namespace tetray::bench
