// The binned surface-area-heuristic split: slower to build than the BIH split, and the cost the
// rebuild policy measures.
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <array>
#include <limits>

#include "render/bvh/bvh_split.hpp"

namespace tetray::render::build {
namespace {

constexpr int kSahBins = 16;

struct Bin {
  Bounds4Builder box;
  std::uint32_t count = 0;
};

// Half the surface area of the tets binned so far (zero while none are).
float binned_area(const Bounds4Builder& box, std::uint32_t count) {
  return count ? box.half_area() : 0.0f;
}
using AxisBins = std::array<std::array<Bin, kSahBins>, 3>;

// The bins of all three axes in one pass over the range, in parallel for the large ranges of
// the top levels (bins merge by exact min, max and sums, so the result is the same however the
// range is cut).
AxisBins bin_centroids(const BuildContext& ctx, const Range& r, const Box3& cb) {
  float scale[3];
  for (int a = 0; a < 3; ++a) {
    const float extent = cb.hi[a] - cb.lo[a];
    scale[a] = extent > 0 ? kSahBins / extent : 0.0f;
  }
  auto fill = [&](std::uint32_t begin, std::uint32_t end, AxisBins& bins) {
    for (std::uint32_t i = begin; i < end; ++i) {
      const BuildItem& item = ctx.items[i];
      const Bounds4& box = ctx.tet_boxes[item.tet];
      for (int a = 0; a < 3; ++a) {
        const int b =
            std::min(kSahBins - 1, static_cast<int>((item.centroid[a] - cb.lo[a]) * scale[a]));
        bins[a][b].box.grow(box);
        ++bins[a][b].count;
      }
    }
  };
  return tbb::parallel_reduce(
      tbb::blocked_range<std::uint32_t>(r.begin, r.end, kParallelGrain), AxisBins{},
      [&](const auto& block, AxisBins bins) {
        fill(block.begin(), block.end(), bins);
        return bins;
      },
      [](AxisBins a, const AxisBins& b) {
        for (int axis = 0; axis < 3; ++axis)
          for (int k = 0; k < kSahBins; ++k) {
            a[axis][k].box.grow(b[axis][k].box.bounds());
            a[axis][k].count += b[axis][k].count;
          }
        return a;
      });
}

}  // namespace

// Binned SAH: the split plane between bins with the lowest area-weighted count.
std::uint32_t split_sah(BuildContext& ctx, const Range& r, Range& left, Range& right) {
  const Box3 cb = centroid_bounds(ctx, r.begin, r.end);
  if (r.depth >= kObjectMedianDepth) return split_object_median(r, left, right);
  const AxisBins all_bins = bin_centroids(ctx, r, cb);
  float best_cost = std::numeric_limits<float>::infinity();
  int best_axis = -1, best_bin = 0;
  for (int axis = 0; axis < 3; ++axis) {
    if (!(cb.hi[axis] - cb.lo[axis] > 0)) continue;
    const auto& bins = all_bins[axis];
    float right_cost[kSahBins];
    Bounds4Builder acc;
    std::uint32_t n = 0;
    for (int b = kSahBins - 1; b > 0; --b) {
      acc.grow(bins[b].box.bounds());
      n += bins[b].count;
      right_cost[b] = binned_area(acc, n) * static_cast<float>(n);
    }
    acc = Bounds4Builder{};
    n = 0;
    for (int b = 0; b < kSahBins - 1; ++b) {
      acc.grow(bins[b].box.bounds());
      n += bins[b].count;
      const float cost = binned_area(acc, n) * static_cast<float>(n) + right_cost[b + 1];
      if (n > 0 && n < r.size() && cost < best_cost) {
        best_cost = cost;
        best_axis = axis;
        best_bin = b;
      }
    }
  }
  if (best_axis < 0) return split_object_median(r, left, right);
  const float scale = kSahBins / (cb.hi[best_axis] - cb.lo[best_axis]);
  const std::uint32_t m = partition_by(ctx, r, [&](const BuildItem& item) {
    const float c = (item.centroid[best_axis] - cb.lo[best_axis]) * scale;
    return std::min(kSahBins - 1, static_cast<int>(c)) <= best_bin;
  });
  left = {r.begin, m, r.box, r.depth + 1};
  right = {m, r.end, r.box, r.depth + 1};
  return m;
}

}  // namespace tetray::render::build
