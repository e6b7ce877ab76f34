// BVH construction (seed 000 §5.1): a BIH-style spatial-median build (no cost function, so it
// is fast) and a binned-SAH build, both partitioning tets by centroid. The top levels are split
// breadth-first, in parallel across the nodes of a level, down to a fixed number of subtrees;
// the subtrees are then built in parallel and laid out one after the other. Every decision
// depends only on the data, so the tree is the same for any thread count, and the subtrees are
// exactly the units of the parallel refit (seed 000 §6.2).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <numeric>

#include "render/bvh/bounds.hpp"
#include "render/bvh/bvh.hpp"
#include "render/bvh/leaf_vertices.hpp"
#include "render/bvh/vertex_order.hpp"

namespace tetray::render {
namespace {

constexpr int kSahBins = 16;
constexpr int kMaxSpatialRetries = 32;
constexpr int kObjectMedianDepth = 48;  // below this depth split by count: depth stays bounded
constexpr std::uint32_t kTargetSubtrees = 64;
constexpr std::uint32_t kParallelGrain = 16384;  // ranges below this are scanned by one thread

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

Box3 centroid_bounds(const BuildContext& ctx, std::uint32_t begin, std::uint32_t end) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::uint32_t>(begin, end, kParallelGrain), Box3{},
      [&](const auto& block, Box3 box) {
        for (std::uint32_t i = block.begin(); i < block.end(); ++i) box.grow(ctx.items[i].centroid);
        return box;
      },
      [](Box3 a, const Box3& b) {
        a.grow(b);
        return a;
      });
}

// Halving split by position in the order array: always makes progress.
std::uint32_t split_object_median(const Range& r, Range& left, Range& right) {
  const std::uint32_t mid = r.begin + r.size() / 2;
  left = {r.begin, mid, r.box, r.depth + 1};
  right = {mid, r.end, r.box, r.depth + 1};
  return mid;
}

std::uint32_t partition_by(BuildContext& ctx, const Range& r, auto&& goes_left) {
  auto* first = ctx.items.data() + r.begin;
  auto* middle = std::partition(first, ctx.items.data() + r.end, goes_left);
  return r.begin + static_cast<std::uint32_t>(middle - first);
}

// BIH-style: halve the spatial interval along its longest axis; when every centroid falls on
// one side, keep halving that side's interval.
std::uint32_t split_bih(BuildContext& ctx, const Range& r, Range& left, Range& right) {
  Box3 box = r.box;
  for (int attempt = 0; attempt < kMaxSpatialRetries && r.depth < kObjectMedianDepth; ++attempt) {
    const int axis = box.longest_axis();
    const float mid = 0.5f * (box.lo[axis] + box.hi[axis]);
    const std::uint32_t m =
        partition_by(ctx, r, [&](const BuildItem& item) { return item.centroid[axis] < mid; });
    if (m != r.begin && m != r.end) {
      left = {r.begin, m, box, r.depth + 1};
      right = {m, r.end, box, r.depth + 1};
      left.box.hi[axis] = mid;
      right.box.lo[axis] = mid;
      return m;
    }
    (m == r.begin ? box.lo : box.hi)[axis] = mid;
  }
  return split_object_median(r, left, right);
}

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

void split(BuildContext& ctx, const Range& r, Range& left, Range& right) {
  if (ctx.options.builder == BvhBuilder::sah) {
    split_sah(ctx, r, left, right);
  } else {
    split_bih(ctx, r, left, right);
  }
}

BvhNode make_leaf(const Range& r) { return BvhNode{{}, r.begin, r.size()}; }
BvhNode make_inner(std::uint32_t first_child) { return BvhNode{{}, first_child, 0}; }

bool is_leaf_range(const BuildContext& ctx, const Range& r) {
  return r.size() <= static_cast<std::uint32_t>(std::max(1, ctx.options.leaf_size));
}

// Depth-first into `out`, whose element `self` is already allocated; children after parents.
void build_subtree(BuildContext& ctx, const Range& r, std::vector<BvhNode>& out,
                   std::uint32_t self) {
  if (is_leaf_range(ctx, r)) {
    out[self] = make_leaf(r);
    return;
  }
  Range left, right;
  split(ctx, r, left, right);
  const auto first = static_cast<std::uint32_t>(out.size());
  out.resize(out.size() + 2);
  out[self] = make_inner(first);
  build_subtree(ctx, left, out, first);
  build_subtree(ctx, right, out, first + 1);
}

void prepare_inputs(const TetVolume& volume, BuildContext& ctx) {
  const std::size_t n = volume.tets.size();
  ctx.items.resize(n);
  if (ctx.options.builder == BvhBuilder::sah) ctx.tet_boxes.resize(n);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n), [&](const auto& block) {
    for (std::size_t t = block.begin(); t != block.end(); ++t) {
      Bounds4Builder builder;
      builder.grow(volume, volume.tets[t]);
      const Bounds4 box = builder.bounds();
      const Vec3f centroid{0.5f * (box.lo[0] + box.hi[0]), 0.5f * (box.lo[1] + box.hi[1]),
                           0.5f * (box.lo[2] + box.hi[2])};
      ctx.items[t] = {centroid, static_cast<std::uint32_t>(t)};
      if (!ctx.tet_boxes.empty()) ctx.tet_boxes[t] = box;
    }
  });
}

struct Pending {
  std::uint32_t node;
  Range range;
};

// Splits the top levels breadth-first until every pending range is small enough to be a
// subtree of its own; returns those, in a deterministic order.
std::vector<Pending> build_top(BuildContext& ctx, std::vector<BvhNode>& top,
                               std::vector<std::uint32_t>& top_inner) {
  const auto n = static_cast<std::uint32_t>(ctx.items.size());
  const std::uint32_t subtree_size = std::max<std::uint32_t>(
      static_cast<std::uint32_t>(std::max(1, ctx.options.leaf_size)), n / kTargetSubtrees);
  std::vector<Pending> level{{0, Range{0, n, centroid_bounds(ctx, 0, n), 0}}}, subtrees;
  top.resize(1);
  while (!level.empty()) {
    std::vector<Pending> to_split;
    for (const Pending& p : level)
      (p.range.size() <= subtree_size ? subtrees : to_split).push_back(p);
    std::vector<Range> halves(2 * to_split.size());
    tbb::parallel_for(std::size_t{0}, to_split.size(), [&](std::size_t k) {
      split(ctx, to_split[k].range, halves[2 * k], halves[2 * k + 1]);
    });
    level.clear();
    for (std::size_t k = 0; k < to_split.size(); ++k) {
      const auto first = static_cast<std::uint32_t>(top.size());
      top.resize(top.size() + 2);
      top[to_split[k].node] = make_inner(first);
      top_inner.push_back(to_split[k].node);
      level.push_back({first, halves[2 * k]});
      level.push_back({first + 1, halves[2 * k + 1]});
    }
  }
  std::reverse(top_inner.begin(), top_inner.end());
  return subtrees;
}

// Places each subtree's root in its top slot and the rest after the top nodes.
void lay_out(std::vector<BvhNode>& top, std::vector<std::vector<BvhNode>>& locals,
             const std::vector<Pending>& pending, Bvh& bvh) {
  std::vector<std::uint32_t> base(locals.size());
  auto next = static_cast<std::uint32_t>(top.size());
  for (std::size_t s = 0; s < locals.size(); ++s) {
    base[s] = next;
    next += static_cast<std::uint32_t>(locals[s].size() - 1);
  }
  bvh.nodes = std::move(top);
  bvh.nodes.resize(next);
  bvh.subtrees.resize(locals.size());
  tbb::parallel_for(std::size_t{0}, locals.size(), [&](std::size_t s) {
    auto remap = [&](BvhNode node) {
      if (!node.is_leaf()) node.first = base[s] + node.first - 1;
      return node;
    };
    const auto& local = locals[s];
    bvh.nodes[pending[s].node] = remap(local[0]);
    for (std::size_t i = 1; i < local.size(); ++i) bvh.nodes[base[s] + i - 1] = remap(local[i]);
    bvh.subtrees[s] = {pending[s].node, base[s],
                       base[s] + static_cast<std::uint32_t>(local.size() - 1)};
    std::vector<BvhNode>().swap(locals[s]);
  });
}

// Puts the tets and their ids into leaf order.
void apply_order(TetVolume& volume, const std::vector<BuildItem>& order) {
  std::vector<Tet> tets(order.size());
  std::vector<std::uint32_t> ids(order.size());
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, order.size()), [&](const auto& block) {
    for (std::size_t i = block.begin(); i != block.end(); ++i) {
      tets[i] = volume.tets[order[i].tet];
      ids[i] = volume.tet_ids[order[i].tet];
    }
  });
  volume.tets.swap(tets);
  volume.tet_ids.swap(ids);
}

}  // namespace

Bvh build_bvh(TetVolume& volume, const BvhBuildOptions& options) {
  Bvh bvh;
  if (volume.tets.empty()) return bvh;
  if (volume.tet_ids.size() != volume.tets.size()) {
    volume.tet_ids.resize(volume.tets.size());
    std::iota(volume.tet_ids.begin(), volume.tet_ids.end(), 0u);
  }
  BuildContext ctx{options, {}, {}};
  prepare_inputs(volume, ctx);
  std::vector<BvhNode> top;
  const std::vector<Pending> pending = build_top(ctx, top, bvh.top_nodes_bottom_up);
  std::vector<std::vector<BvhNode>> locals(pending.size());
  tbb::parallel_for(std::size_t{0}, pending.size(), [&](std::size_t s) {
    locals[s].resize(1);
    build_subtree(ctx, pending[s].range, locals[s], 0);
  });
  lay_out(top, locals, pending, bvh);
  apply_order(volume, ctx.items);
  renumber_vertices(volume, bvh);
  list_leaf_vertices(volume, bvh);
  refit_bvh(volume, bvh, true);
  bvh.sah_cost_at_build = bvh.sah_cost_now;
  return bvh;
}

}  // namespace tetray::render
