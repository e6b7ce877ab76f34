// The hit filter of depth peeling (Wald et al. 2007, §8.5: transparency by secondary rays from
// the primary packet's origin): a layer keeps only hits strictly after the previous layer's hit
// in the tie order of docs/architecture.md §3, distance first, then the smaller tie key. A hit
// at the previous layer's very distance (a shared edge or vertex of two tets) with a larger key
// is the next layer, one with the same or a smaller key was already peeled: every hit is peeled
// once, none is lost or doubled. It wraps the clip region's filter (render/scene/clip_region.hpp),
// so a layer is clipped like the first hit.
#pragma once

#include <cstdint>

#include "render/bvh/bvh.hpp"
#include "render/core/simd.hpp"
#include "render/core/vec.hpp"

namespace tetray::render {

template <typename Inner>
struct AfterLayerFilter {
  static constexpr bool kKeepsAll = false;

  template <typename F>
  auto keeps(Vec3f eye, F t, F dx, F dy, F dz, int base, std::uint32_t key) const {
    const F previous = simd::load(previous_t + base, F{});
    // key > previous key, as !(previous key > key - 1); nothing is after key 0 at one distance.
    const auto later_key =
        key == 0 ? previous != previous : !simd::greater(previous_key + base, key - 1, F{});
    auto after = simd::either(t > previous, simd::both(t == previous, later_key));
    if constexpr (!Inner::kKeepsAll)
      after = simd::both(after, inner.keeps(eye, t, dx, dy, dz, base, key));
    return after;
  }

  Inner inner;
  const float* previous_t;            // per ray, the previous layer's distance
  const std::uint32_t* previous_key;  // and tie key
};

// The node filter of a layer: a ray's box test starts at its previous layer's distance, so the
// traversal skips the subtrees in front of it, whose hits the hit filter would drop (the robust
// far distance of a box holding a hit is never below it). Wraps the clip region's node filter.
template <typename Inner>
struct AfterLayerNodeFilter {
  bool discards(const Bounds4& b) const { return inner.discards(b); }
  template <typename V>
  V ray_tmin(int r, V) const {
    return simd::load(previous_t + r, V{});
  }

  Inner inner;
  const float* previous_t;
};

}  // namespace tetray::render
