// One rank's fragments of a run of pixels as they arrive from it, and the merge of every rank's
// fragments of one pixel by a sort: what both fragment compositors (fragment_composite.cpp
// gathers to the root, fragment_stripes.cpp splits the image into stripes) do per pixel
// (fragment_merge.hpp merges the common cases without the sort).
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "render/core/fragments.hpp"

namespace tetray::render {

// A rank's pixels [first, last) (it has none outside them) as it sent them: its begin offsets of
// those pixels (last - first + 1 of them, where offsets[0] is where `fragments` starts) and the
// fragments.
template <typename F>
struct FragmentRun {
  std::uint32_t first = 0, last = 0;
  const std::uint32_t* offsets = nullptr;
  const F* fragments = nullptr;

  std::span<const F> at(std::size_t p) const {
    if (p < first || p >= last) return {};
    const std::uint32_t* o = offsets + (p - first);
    return {fragments + (o[0] - offsets[0]), o[1] - o[0]};
  }
};

// The pixels [first, last) of [from, to) from the first to the last with any fragment of
// `image`: what a rank sends of them (first == last when it has none there).
template <typename F>
std::pair<std::uint32_t, std::uint32_t> covered_pixels(const BasicFragmentImage<F>& image,
                                                       std::size_t from, std::size_t to) {
  const std::vector<std::uint32_t>& begin = image.begin;
  while (from < to && begin[from + 1] == begin[from]) ++from;
  while (to > from && begin[to] == begin[to - 1]) --to;
  return {static_cast<std::uint32_t>(from), static_cast<std::uint32_t>(to)};
}

// Whether `layers` are in the merge's order, each in front of the next.
template <typename F>
bool in_order(std::span<const F> layers) {
  for (std::size_t k = 1; k < layers.size(); ++k) {
    if (!in_front_of(layers[k - 1], layers[k])) return false;
  }
  return true;
}

// Whether a pixel's fragments from one rank are already what the merge keeps of them: front to
// back in the merge's order, none opaque before the last, at most max_layers (what trace_layers
// gives). A pixel only one rank covers then needs no sort.
template <typename F>
bool already_kept(std::span<const F> layers, std::size_t max_layers) {
  if (layers.size() > max_layers || !in_order(layers)) return false;
  return std::none_of(layers.begin(), layers.end() - (layers.empty() ? 0 : 1),
                      [](const F& f) { return f.rgba[3] >= 1; });
}

// Pixel p's kept fragments of all runs together (kept_layers), in order: the one covering rank's
// own where they are already kept, otherwise gathered into `scratch` (rank order) and sorted.
template <typename F>
std::span<const F> kept_of_runs(std::span<const FragmentRun<F>> runs, std::size_t p,
                                std::size_t max_layers, std::vector<F>& scratch) {
  const FragmentRun<F>* only = nullptr;
  std::size_t contributors = 0;
  for (const FragmentRun<F>& run : runs) {
    if (run.at(p).empty()) continue;
    ++contributors;
    only = &run;
  }
  if (contributors == 0) return {};
  scratch.clear();
  if (contributors == 1) {
    const std::span<const F> mine = only->at(p);
    if (already_kept(mine, max_layers)) return mine;
    scratch.assign(mine.begin(), mine.end());
  } else {
    for (const FragmentRun<F>& run : runs) {
      const std::span<const F> layers = run.at(p);
      scratch.insert(scratch.end(), layers.begin(), layers.end());
    }
  }
  return std::span<const F>(scratch).first(kept_layers(scratch, max_layers));
}

}  // namespace tetray::render
