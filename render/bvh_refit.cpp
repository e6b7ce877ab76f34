// Refitting the implicit BVH for a new time step (seed 000 §6.2, Schema II): the recorded
// subtrees are refit in parallel, children before parents, then the few top nodes. A leaf's
// bound is that of its distinct vertices (leaf_vertices.hpp), read once each instead of once
// per tet corner. Field-only refits touch only the scalar ranges. The SAH cost of the refit tree,
// the quality measure of the rebuild policy, is summed on the way in a fixed order, so it too is
// independent of the thread count.
#include <tbb/parallel_for.h>

#include <limits>

#include "render/bounds.hpp"
#include "render/bvh.hpp"

namespace tetray::render {
namespace {

// Writes dimensions [first_axis, 4) of `b` into `node`: 0 for x, y, z and f, 3 for the scalar
// range alone (a field-only refit leaves the geometry as it is).
void set_bounds(BvhNode& node, const Bounds4& b, int first_axis) {
  for (int a = first_axis; a < 4; ++a) {
    node.bounds.lo[a] = b.lo[a];
    node.bounds.hi[a] = b.hi[a];
  }
}

// Two bounds grown in turn and merged: two independent min/max chains instead of one, which
// halves the latency a leaf waits on (about 5% of a refit; four chains were slower again).
template <bool geometry>
void fit_leaf(const TetVolume& volume, const Bvh& bvh, std::uint32_t i, BvhNode& node) {
  Bounds4Builder even, odd;
  const std::uint32_t end = bvh.leaf_vertex_begin[i + 1];
  std::uint32_t k = bvh.leaf_vertex_begin[i];
  for (; k + 1 < end; k += 2) {
    even.grow(volume.vertices[bvh.leaf_vertices[k]]);
    odd.grow(volume.vertices[bvh.leaf_vertices[k + 1]]);
  }
  if (k < end) even.grow(volume.vertices[bvh.leaf_vertices[k]]);
  even.grow(odd.bounds());
  set_bounds(node, even.bounds(), geometry ? 0 : 3);
}

template <bool geometry>
void fit_inner(std::vector<BvhNode>& nodes, BvhNode& node) {
  Bounds4Builder b;
  b.grow(nodes[node.first].bounds);
  b.grow(nodes[node.first + 1].bounds);
  set_bounds(node, b.bounds(), geometry ? 0 : 3);
}

// Fits node i and returns its term of the SAH cost (needed only when the geometry changed).
template <bool geometry>
double fit_node(const TetVolume& volume, Bvh& bvh, std::uint32_t i) {
  BvhNode& node = bvh.nodes[i];
  if (node.is_leaf()) {
    fit_leaf<geometry>(volume, bvh, i, node);
    return geometry ? static_cast<double>(half_area(node.bounds)) * node.count : 0.0;
  }
  fit_inner<geometry>(bvh.nodes, node);
  return geometry ? half_area(node.bounds) : 0.0;
}

template <bool geometry>
void refit(const TetVolume& volume, Bvh& bvh) {
  std::vector<double> subtree_cost(bvh.subtrees.size());
  tbb::parallel_for(std::size_t{0}, bvh.subtrees.size(), [&](std::size_t s) {
    const Bvh::Subtree& st = bvh.subtrees[s];
    double cost = 0;
    for (std::uint32_t i = st.end; i-- > st.begin;) cost += fit_node<geometry>(volume, bvh, i);
    subtree_cost[s] = cost + fit_node<geometry>(volume, bvh, st.root);
  });
  double cost = 0;
  for (double c : subtree_cost) cost += c;
  for (std::uint32_t i : bvh.top_nodes_bottom_up) cost += fit_node<geometry>(volume, bvh, i);
  if (geometry) {
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
