// The merge of a pixel's fragments from its ranks without a sort, where every rank's list is in
// the merge's order (as trace_layers and the walk give them) and they are few: each fragment's
// place in the merged order is its index in its own list plus the other lists' fragments in
// front of it, counted independently of every other fragment's place. The merged order is then
// blended as blend_layers blends kept_layers' result, bit for bit: in the merge's total order
// (depth, then the key no two ranks share) the merged sequence is the sorted one.
//
// Why not a sort: for the two to four layers of two ranks a sort and the copy before it cost
// about twice the merge. Why two passes over a block of pixels (fragment_stripes.cpp): a pixel's
// blend reads the order the merge just wrote through addresses known only then, and blending
// right after the merge stalled on it; merging a block first, then blending it, took half the
// time.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>

#include "render/composite/fragment_runs.hpp"

namespace tetray::render {

// The most fragments (and lists) of one pixel merged in place; more go through the sort.
inline constexpr std::size_t kMergedFragments = 16;
inline constexpr std::size_t kMergedLists = 8;
// merged_order's answer for a pixel it leaves to the sort.
inline constexpr std::size_t kNotMerged = ~std::size_t{0};

// in_front_of without short-circuits, so that the merge adds compare results instead of
// branching on them where two ranks' layers interleave.
template <typename F>
bool nearer(const F& a, const F& b) {
  return (a.depth_in < b.depth_in) | ((a.depth_in == b.depth_in) & (a.key < b.key));
}

// Two lists of NA and NB fragments, a's first where two are equal: one compare per pair, which
// places both (b_j in front of a_i or not), unrolled.
template <std::size_t NA, std::size_t NB, typename F>
void merge_fixed(const F* a, const F* b, const F** order) {
  std::array<std::size_t, NA> place_a;
  std::array<std::size_t, NB> place_b;
  for (std::size_t i = 0; i < NA; ++i) place_a[i] = i;
  for (std::size_t j = 0; j < NB; ++j) place_b[j] = j;
  for (std::size_t i = 0; i < NA; ++i) {
    for (std::size_t j = 0; j < NB; ++j) {
      const bool b_first = nearer(b[j], a[i]);
      place_a[i] += b_first;
      place_b[j] += !b_first;
    }
  }
  for (std::size_t i = 0; i < NA; ++i) order[place_a[i]] = a + i;
  for (std::size_t j = 0; j < NB; ++j) order[place_b[j]] = b + j;
}

// Any number of ordered lists, an earlier list's first where two are equal.
template <typename F>
void merge_lists(std::span<const std::span<const F>> lists, const F** order) {
  for (std::size_t l = 0; l < lists.size(); ++l) {
    for (std::size_t i = 0; i < lists[l].size(); ++i) {
      const F& x = lists[l][i];
      std::size_t before = i;
      for (std::size_t m = 0; m < l; ++m) {
        for (const F& y : lists[m]) before += !nearer(x, y);
      }
      for (std::size_t m = l + 1; m < lists.size(); ++m) {
        for (const F& y : lists[m]) before += nearer(y, x);
      }
      order[before] = &x;
    }
  }
}

// merge_fixed for the sizes of case k = 4 (NA - 1) + NB - 1 of the 16 up to four by four.
template <typename F, std::size_t... K>
void merge_sized(std::size_t k, const F* a, const F* b, const F** order,
                 std::index_sequence<K...>) {
  (void)((k == K && (merge_fixed<K / 4 + 1, K % 4 + 1>(a, b, order), true)) || ...);
}

// Two lists: unrolled for up to four fragments each (the layers of transparent surfaces).
template <typename F>
void merge_two(std::span<const F> a, std::span<const F> b, const F** order) {
  constexpr std::size_t kUnrolled = 4;
  if (a.size() > kUnrolled || b.size() > kUnrolled) {
    const std::span<const F> lists[] = {a, b};
    return merge_lists<F>(lists, order);
  }
  merge_sized(kUnrolled * (a.size() - 1) + b.size() - 1, a.data(), b.data(), order,
              std::make_index_sequence<kUnrolled * kUnrolled>());
}

// Pixel p's fragments of all runs in the merge's order, into `order` (kMergedFragments
// entries): how many, or kNotMerged where a rank's list is out of order or there are too many.
template <typename F>
std::size_t merged_order(std::span<const FragmentRun<F>> runs, std::size_t p, const F** order) {
  // Left uninitialised: an array of spans was cleared for every pixel, a fifth of the merge.
  const F* list_data[kMergedLists];
  std::size_t list_size[kMergedLists];
  std::size_t count = 0, total = 0;
  for (const FragmentRun<F>& run : runs) {
    const std::span<const F> layers = run.at(p);
    if (layers.empty()) continue;
    if (count == kMergedLists || !in_order(layers)) return kNotMerged;
    list_data[count] = layers.data();
    list_size[count++] = layers.size();
    total += layers.size();
  }
  if (total > kMergedFragments) return kNotMerged;
  if (count == 1) {
    for (std::size_t k = 0; k < total; ++k) order[k] = list_data[0] + k;
  } else if (count == 2) {
    merge_two<F>({list_data[0], list_size[0]}, {list_data[1], list_size[1]}, order);
  } else if (count > 2) {
    std::span<const F> lists[kMergedLists];
    for (std::size_t l = 0; l < count; ++l) lists[l] = {list_data[l], list_size[l]};
    merge_lists<F>({lists, count}, order);
  }
  return total;
}

// blend_layers of the merged order's kept fragments: front to back up to max_layers and the
// first opaque one.
template <typename F>
void blend_order(const F* const* order, std::size_t count, std::size_t max_layers, float rgba[4],
                 float& depth, std::uint32_t& key) {
  double out[4] = {0, 0, 0, 0};
  std::size_t kept = 0;
  while (kept < std::min(count, max_layers)) {
    add_behind(out, *order[kept]);
    if (order[kept++]->rgba[3] >= 1) break;
  }
  for (int c = 0; c < 4; ++c) rgba[c] = static_cast<float>(out[c]);
  depth = kept > 0 ? order[0]->depth_in : std::numeric_limits<float>::infinity();
  key = kept > 0 ? order[0]->key : kNoHit;
}

}  // namespace tetray::render
