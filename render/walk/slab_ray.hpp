// The slab test of a ray against an axis-aligned box (Ize 2013), for the two trees a walk
// searches: the boundary faces' (boundary_faces.hpp) and the volume's BVH when skipping empty
// space (empty_space.hpp). Both only cull, so every box is grown (slab_pad) before the test: a
// box may be kept that the ray misses, never lost when a face or tet inside it is hit. A ray
// parallel to an axis with its origin exactly on a grown side gives 0 x inf = NaN there, which
// keeps the box on the low side and culls it on the high side; either is right, since such a
// ray runs a whole pad away from what the box holds.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>

#include "render/walk/ray_frame.hpp"

namespace tetray::render {

// The ray as the box test reads it: 1/d per axis (+-inf along an axis the ray does not move on).
struct SlabRay {
  double origin[3];
  double inverse[3];

  explicit SlabRay(const RayFrame& frame) {
    for (int axis = 0; axis < 3; ++axis) {
      origin[axis] = frame.origin[axis];
      inverse[axis] = 1.0 / frame.direction[axis];
    }
  }
};

// The growth of a box side at `lo`..`hi` that covers the rounding of the tests.
inline double slab_pad(double lo, double hi) {
  return 1e-6 * (1.0 + std::max(std::abs(lo), std::abs(hi)));
}

// Where the ray enters the box [lo, hi] (already grown) within [t_lo, t_hi]; NaN when it misses
// it (every comparison with a miss is false).
template <typename Scalar>
double slab_entry(const SlabRay& ray, const Scalar* lo, const Scalar* hi, double t_lo,
                  double t_hi) {
  for (int axis = 0; axis < 3; ++axis) {
    const double t0 = (lo[axis] - ray.origin[axis]) * ray.inverse[axis];
    const double t1 = (hi[axis] - ray.origin[axis]) * ray.inverse[axis];
    t_lo = std::max(t_lo, std::min(t0, t1));
    t_hi = std::min(t_hi, std::max(t0, t1));
  }
  return t_lo <= t_hi ? t_lo : std::numeric_limits<double>::quiet_NaN();
}

// As slab_entry, for a box of floats grown here in double.
inline double grown_slab_entry(const SlabRay& ray, const float* lo, const float* hi, double t_lo,
                               double t_hi) {
  double glo[3], ghi[3];
  for (int axis = 0; axis < 3; ++axis) {
    const double pad = slab_pad(lo[axis], hi[axis]);
    glo[axis] = lo[axis] - pad;
    ghi[axis] = hi[axis] + pad;
  }
  return slab_entry(ray, glo, ghi, t_lo, t_hi);
}

// Grows a box of floats in place, rounded outwards, as grown_slab_entry would in double.
inline void grow_box(float* lo, float* hi) {
  for (int axis = 0; axis < 3; ++axis) {
    const double pad = slab_pad(lo[axis], hi[axis]);
    const double l = lo[axis] - pad, h = hi[axis] + pad;
    lo[axis] = static_cast<float>(l);
    hi[axis] = static_cast<float>(h);
    if (lo[axis] > l) lo[axis] = std::nextafter(lo[axis], -std::numeric_limits<float>::infinity());
    if (hi[axis] < h) hi[axis] = std::nextafter(hi[axis], std::numeric_limits<float>::infinity());
  }
}

// Visits the leaves of a binary tree of boxes (node 0 the root; an inner node's children at
// first_child(i) and first_child(i) + 1) whose boxes the ray enters no later than `t_best`,
// nearer child first, so that hits found early prune the rest: `leaf(i)` may lower t_best.
// entry_of(i): where the ray enters node i's box within [t_from, t_best] (slab_entry; NaN: it
// misses, or the node is to be skipped). kStack bounds the pending nodes: one per level, plus
// the pair just pushed.
template <int kStack, typename EntryOf, typename IsLeaf, typename FirstChild, typename Leaf>
void visit_nearest_first(const double& t_best, EntryOf&& entry_of, IsLeaf&& is_leaf,
                         FirstChild&& first_child, Leaf&& leaf) {
  struct Pending {
    std::uint32_t node;
    double t;  // where the ray enters its box; beyond the best hit found since: skipped
  };
  Pending stack[kStack];
  int top = 0;
  const double root_t = entry_of(0u);
  if (!(root_t <= t_best)) return;
  stack[top++] = {0, root_t};
  while (top > 0) {
    const Pending pending = stack[--top];
    if (!(pending.t <= t_best)) continue;
    if (is_leaf(pending.node)) {
      leaf(pending.node);
      continue;
    }
    const std::uint32_t first = first_child(pending.node);
    const Pending left{first, entry_of(first)}, right{first + 1, entry_of(first + 1)};
    // The nearer child last, so it is searched first.
    const bool right_nearer = right.t < left.t;
    for (const Pending& p : {right_nearer ? left : right, right_nearer ? right : left}) {
      if (p.t <= t_best) stack[top++] = p;
    }
  }
}

}  // namespace tetray::render
