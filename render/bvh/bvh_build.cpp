// BVH construction (Wald et al. 2007, §5.1) with the split the options name (bih_split.cpp or
// sah_split.cpp), both partitioning tets by centroid. The top levels are split
// breadth-first, in parallel across the nodes of a level, down to a fixed number of subtrees;
// the subtrees are then built in parallel and laid out one after the other. Every decision
// depends only on the data, so the tree is the same for any thread count, and the subtrees are
// exactly the units of the parallel refit (Wald et al. 2007, §6.2).
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <array>
#include <numeric>

#include "render/bvh/bvh_split.hpp"
#include "render/bvh/leaf_vertices.hpp"
#include "render/bvh/vertex_order.hpp"

namespace tetray::render {
namespace {

using build::BuildContext;
using build::BuildItem;
using build::Range;

constexpr std::uint32_t kTargetSubtrees = 64;

void split(BuildContext& ctx, const Range& r, Range& left, Range& right) {
  if (ctx.options.builder == BvhBuilder::sah) {
    build::split_sah(ctx, r, left, right);
  } else {
    build::split_bih(ctx, r, left, right);
  }
}

BvhNode make_leaf(const Range& r) { return BvhNode{{}, r.begin, r.size()}; }
BvhNode make_inner(std::uint32_t first_child) { return BvhNode{{}, first_child, 0}; }

std::uint32_t max_leaf_tets(const BuildContext& ctx) {
  return static_cast<std::uint32_t>(std::clamp(ctx.options.leaf_size, 1, kMaxLeafSize));
}

bool is_leaf_range(const BuildContext& ctx, const Range& r) {
  return r.size() <= max_leaf_tets(ctx);
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
std::vector<Pending> build_top(BuildContext& ctx, LargeArray<BvhNode>& top,
                               std::vector<std::uint32_t>& top_inner) {
  const auto n = static_cast<std::uint32_t>(ctx.items.size());
  const std::uint32_t subtree_size =
      std::max<std::uint32_t>(max_leaf_tets(ctx), n / kTargetSubtrees);
  std::vector<Pending> level{{0, Range{0, n, build::centroid_bounds(ctx, 0, n), 0}}}, subtrees;
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
void lay_out(LargeArray<BvhNode>& top, std::vector<std::vector<BvhNode>>& locals,
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
  LargeArray<Tet> tets(order.size());
  LargeArray<std::uint32_t> ids(order.size());
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
  LargeArray<BvhNode> top;
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
