// Refitting the implicit BVH for a new time step (Wald et al. 2007, §6.2, Schema II): the recorded
// subtrees are refit in parallel, each depth first with children before parents, then the few top
// nodes. A leaf's bound is that of its distinct vertices (leaf_vertices.hpp), read once each
// instead of once per tet corner. Field-only refits touch only the scalar ranges. The SAH cost of
// the refit tree, the quality measure of the rebuild policy, is summed on the way in a fixed order,
// so it too is independent of the thread count.
#include <tbb/parallel_for.h>

#include <limits>

#include "render/bvh/bounds.hpp"
#include "render/bvh/bvh.hpp"

namespace tetray::render {
namespace {

// A leaf's bound is that of its listed vertices, from whole vertices, four to a register. A
// field-only refit takes its scalar range from the same loads: gathering the values sixteen at
// a time made the field-only update at 4M tets 1.4x slower than the whole one on an AMD EPYC
// (the same lines are read).
Bounds4Builder leaf_bound(const TetVolume& volume, const Bvh& bvh, std::uint32_t i) {
  const std::uint32_t begin = bvh.leaf_vertex_begin[i];
  Bounds4Builder b;
  simd::min_max_rows(&volume.vertices.data()->x, bvh.leaf_vertices.data() + begin,
                     static_cast<int>(bvh.leaf_vertex_begin[i + 1] - begin), b.lo, b.hi);
  return b;
}

Bounds4Builder inner_bound(const LargeArray<BvhNode>& nodes, const BvhNode& node) {
  Bounds4Builder b;
  b.grow(nodes[node.first].bounds);
  b.grow(nodes[node.first + 1].bounds);
  return b;
}

// Fits node i: its whole bound when the geometry changed, adding its terms of the SAH cost to
// `cost` (the area terms weighted by the node's tets, one for an inner node) from the bound still
// in registers and without horizontal sums or conversions (a node's own work is a few dozen
// instructions, and the SAH term in scalar double had been a tenth of a geometry refit); only
// its scalar range otherwise.
template <bool geometry>
void fit_node(const TetVolume& volume, Bvh& bvh, std::uint32_t i, simd::Float4& cost) {
  BvhNode& node = bvh.nodes[i];
  const bool leaf = node.is_leaf();
  const Bounds4Builder b = leaf ? leaf_bound(volume, bvh, i) : inner_bound(bvh.nodes, node);
  if constexpr (geometry) {
    node.bounds = b.bounds();
    cost = cost + b.area_terms() * simd::Float4(leaf ? static_cast<float>(node.count) : 1.0f);
  } else {
    const Bounds4 range = b.bounds();
    node.bounds.lo[3] = range.lo[3];
    node.bounds.hi[3] = range.hi[3];
  }
}

// Fits the subtree under node i, children before parents, depth first: its leaves come in
// ascending order, and with them their vertex lists and the vertices in the order the leaves
// first use them (vertex_order.hpp), read front to back. Fitting the nodes in descending index
// order, which also puts children first, read them back to front: the refit at 14M tets took
// twice as long, its vertex loads waiting on memory.
template <bool geometry>
void fit_below(const TetVolume& volume, Bvh& bvh, std::uint32_t i, simd::Float4& cost) {
  const BvhNode& node = bvh.nodes[i];
  if (!node.is_leaf()) {
    fit_below<geometry>(volume, bvh, node.first, cost);
    fit_below<geometry>(volume, bvh, node.first + 1, cost);
  }
  fit_node<geometry>(volume, bvh, i, cost);
}

template <bool geometry>
void refit(const TetVolume& volume, Bvh& bvh) {
  // Lanewise sums in a fixed order per subtree, then over the subtrees in order: the cost does
  // not depend on the thread count.
  std::vector<simd::Float4> subtree_cost(bvh.subtrees.size(), simd::Float4(0.0f));
  tbb::parallel_for(std::size_t{0}, bvh.subtrees.size(), [&](std::size_t s) {
    const Bvh::Subtree& st = bvh.subtrees[s];
    simd::Float4 cost(0.0f);
    fit_below<geometry>(volume, bvh, st.root, cost);
    subtree_cost[s] = cost;
  });
  simd::Float4 top(0.0f);
  for (std::uint32_t i : bvh.top_nodes_bottom_up) fit_node<geometry>(volume, bvh, i, top);
  if (geometry) {
    double cost = simd::sum3(top);
    for (const simd::Float4& c : subtree_cost) cost += simd::sum3(c);
    const float root_area = half_area(bvh.nodes[0].bounds);
    bvh.sah_cost_now = root_area > 0 ? cost / root_area : 0.0;
  }
}

}  // namespace

void refit_bvh(const TetVolume& volume, Bvh& bvh, bool geometry) {
  if (bvh.empty()) return;
  if (geometry) {
    refit<true>(volume, bvh);
  } else {
    refit<false>(volume, bvh);
  }
}

}  // namespace tetray::render
