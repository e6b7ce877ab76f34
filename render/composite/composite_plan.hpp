// Which ranks exchange what, and in how many rounds (the schedule of compositor.hpp).
//
// Radix-k (Peterka et al., "A configurable algorithm for parallel image-compositing
// applications", SC 2009) factors the rank count P = k_1 k_2 ... k_r: in round i the ranks that
// differ only in digit i (mixed radix) form a group of k_i, split their current span into k_i
// parts and each keeps one part, receiving it from the k_i - 1 others. Binary swap is radix-k
// with every k = 2. A rank count with a prime factor above kMaxPrimeRadix is first folded: the
// ranks past the largest usable count send their whole image to a partner, which composites it
// before the rounds. The plain gather is the schedule with no rounds: every rank's piece is the
// whole image and goes straight to the root.
#pragma once

#include <algorithm>
#include <vector>

#include "render/composite/composite.hpp"

namespace tetray::render {

inline constexpr int kMaxPrimeRadix = 7;
inline constexpr int kMaxRadix = 8;

struct CompositePlan {
  int rank_count = 1;
  int swap_count = 1;        // ranks that take part in the rounds: virtual ranks 0..swap_count-1
  std::vector<int> radices;  // k of each round; their product is swap_count

  int folded_count() const { return rank_count - swap_count; }
  // Message rounds of the schedule: the fold (if any), the radix rounds, then the assembly on
  // the root: the radix rounds in reverse, or one gather when there were none.
  int round_count() const {
    const auto rounds = static_cast<int>(radices.size());
    return (folded_count() > 0 ? 1 : 0) + rounds + std::max(rounds, 1);
  }
};

// `algorithm` automatic is radix-k (composite_plan.cpp says why).
CompositePlan make_plan(int rank_count, CompositeAlgorithm algorithm);

// The digit of `virtual_rank` in round `round` and the distance between group members.
struct RoundPosition {
  int digit = 0;
  int stride = 1;
};
RoundPosition round_position(const CompositePlan& plan, int round, int virtual_rank);

// CompositeRows::automatic interlaces when the tallest rank's active rows are at most this
// share of the image's height (docs/scaling.md: where each order wins).
inline constexpr double kInterlaceBelow = 0.25;

// Whether the schedule takes the rows interlaced, from the choice and the agreed tallest active
// rows (the same on every rank).
bool interlace_rows(CompositeRows rows, int tallest_active_rows, int height);

}  // namespace tetray::render
