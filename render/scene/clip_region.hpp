// Clipping (Wald et al. 2007, §7): a scene keeps only the part of space inside an optional box
// and behind up to six planes. The traversal skips subtrees whose box lies entirely outside the
// kept region, as it skips subtrees out of iso-range; a hit outside it is discarded and the ray
// goes on, so surfaces behind a cut are seen. Without a region none of this is compiled into the
// trace (docs/architecture.md §7: NoNodeFilter, NoHitFilter).
#pragma once

#include <algorithm>
#include <cstdint>

#include "render/bvh/bvh.hpp"
#include "render/core/simd.hpp"
#include "render/core/vec.hpp"

namespace tetray::render {

inline constexpr int kMaxClipPlanes = 6;

// Keeps the half-space dot(x - point, normal) <= 0: the normal points to the part cut away.
struct ClipPlane {
  Vec3d point, normal;
};

// In world coordinates, as a scene gives it.
struct ClipRegion {
  bool has_box = false;
  Vec3d box_lo, box_hi;
  int plane_count = 0;
  ClipPlane planes[kMaxClipPlanes];

  bool empty() const { return !has_box && plane_count == 0; }
};

// The region in a volume's local coordinates and float, as the trace tests it. Each plane is
// dot(n, x) <= offset. Every rank of a scene shares the local origin, so the float region,
// and with it every keep decision, is the same bitwise on every rank.
struct LocalClip {
  bool has_box = false;
  Vec3f lo, hi;
  int plane_count = 0;
  Vec3f normal[kMaxClipPlanes];
  float offset[kMaxClipPlanes];
  // Subtrees are skipped only when they lie farther outside than this: a hit point computed in
  // float may stray from its node's box by rounding, and the per-hit test must decide it alone,
  // or the image would depend on the BVH (and so on the rank count).
  float margin = 0;

  LocalClip() = default;
  LocalClip(const ClipRegion& region, Vec3d origin, float magnitude);

  // Whether no point of the box can be kept.
  bool discards(const Bounds4& b) const {
    if (has_box) {
      for (int a = 0; a < 3; ++a) {
        if (b.hi[a] < lo[a] - margin || b.lo[a] > hi[a] + margin) return true;
      }
    }
    for (int k = 0; k < plane_count; ++k) {
      float nearest = 0;  // the smallest dot(n, x) over the box's corners
      for (int a = 0; a < 3; ++a)
        nearest += std::min(normal[k][a] * b.lo[a], normal[k][a] * b.hi[a]);
      if (nearest > offset[k] + margin) return true;
    }
    return false;
  }

  // Lanes whose point (x, y, z) is kept: inside the box (faces included) and not in front of
  // any plane.
  template <typename F>
  auto keeps(F x, F y, F z) const {
    auto kept = x == x;  // all lanes (a hit point is never NaN)
    if (has_box) {
      kept = simd::both(kept, simd::both(x >= F(lo.x), x <= F(hi.x)));
      kept = simd::both(kept, simd::both(y >= F(lo.y), y <= F(hi.y)));
      kept = simd::both(kept, simd::both(z >= F(lo.z), z <= F(hi.z)));
    }
    for (int k = 0; k < plane_count; ++k) {
      const F side = normal[k].x * x + normal[k].y * y + normal[k].z * z;
      kept = simd::both(kept, side <= F(offset[k]));
    }
    return kept;
  }
};

// The node and hit filters of the traversal and the intersector without a clip region: they
// keep everything and compile to nothing.
struct NoNodeFilter {
  NoNodeFilter() = default;
  explicit NoNodeFilter(const LocalClip&) {}
  static constexpr bool discards(const Bounds4&) { return false; }
  // The distance below which rays r.. seek no hits, for their box tests: 0, the eye.
  template <typename V>
  static V ray_tmin(int, V) {
    return V(0.0f);
  }
};
struct NoHitFilter {
  static constexpr bool kKeepsAll = true;
  NoHitFilter() = default;
  explicit NoHitFilter(const LocalClip&) {}
};

// A hit filter with kKeepsAll false answers keeps(eye, t, dx, dy, dz, base, key): the lanes of
// rays base.. (directions d, eye `eye`) whose hit at distance t on a primitive of tie key `key`
// it keeps.

// With a region: a node is skipped when discarded, a hit kept when its point is kept.
struct ClipNodeFilter {
  explicit ClipNodeFilter(const LocalClip& region) : clip(&region) {}
  bool discards(const Bounds4& b) const { return clip->discards(b); }
  template <typename V>
  static V ray_tmin(int, V) {
    return V(0.0f);
  }
  const LocalClip* clip;
};
struct ClipHitFilter {
  static constexpr bool kKeepsAll = false;
  explicit ClipHitFilter(const LocalClip& region) : clip(&region) {}
  template <typename F>
  auto keeps(Vec3f eye, F t, F dx, F dy, F dz, int, std::uint32_t) const {
    return clip->keeps(eye.x + t * dx, eye.y + t * dy, eye.z + t * dz);
  }
  const LocalClip* clip;
};

}  // namespace tetray::render
