// The pieces the BVH builders share (Wald et al. 2007, §5.1): the ranges of tets being split,
// the build items that carry their centroids, and the two ways a range is split, one file per
// builder (bih_split.cpp, sah_split.cpp). bvh_build.cpp drives them.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "render/bvh/bounds.hpp"
#include "render/bvh/bvh.hpp"

namespace tetray::render::build {

inline constexpr int kObjectMedianDepth =
    48;  // below this depth split by count: depth stays bounded
inline constexpr std::uint32_t kParallelGrain =
    16384;  // ranges below this are scanned by one thread

struct Range {
  std::uint32_t begin, end;
  Box3 box;  // BIH: the spatial interval being split; unused by SAH
  int depth;
  std::uint32_t size() const { return end - begin; }
};

// A tet as the partitions move it: its centroid travels with it, so partitioning reads and
// writes memory in order instead of gathering centroids by index.
struct BuildItem {
  Vec3f centroid;
  std::uint32_t tet;
};

struct BuildContext {
  const BvhBuildOptions& options;
  std::vector<BuildItem> items;    // tets in build order
  std::vector<Bounds4> tet_boxes;  // SAH only, by tet
};

// The bounds of the centroids of items [begin, end), in parallel for large ranges.
Box3 centroid_bounds(const BuildContext& ctx, std::uint32_t begin, std::uint32_t end);

// Halving split by position in the order array: always makes progress.
inline std::uint32_t split_object_median(const Range& r, Range& left, Range& right) {
  const std::uint32_t mid = r.begin + r.size() / 2;
  left = {r.begin, mid, r.box, r.depth + 1};
  right = {mid, r.end, r.box, r.depth + 1};
  return mid;
}

// Moves the items of `r` for which goes_left holds to its front; returns where the rest begin.
inline std::uint32_t partition_by(BuildContext& ctx, const Range& r, auto&& goes_left) {
  auto* first = ctx.items.data() + r.begin;
  auto* middle = std::partition(first, ctx.items.data() + r.end, goes_left);
  return r.begin + static_cast<std::uint32_t>(middle - first);
}

// Each splits `r` into `left` and `right` (both non-empty) and returns where `right` begins.
std::uint32_t split_bih(BuildContext& ctx, const Range& r, Range& left, Range& right);
std::uint32_t split_sah(BuildContext& ctx, const Range& r, Range& left, Range& right);

}  // namespace tetray::render::build
