// Axis-aligned boxes used while building and refitting the BVH.
#pragma once

#include <limits>

#include "render/bvh.hpp"
#include "render/vec.hpp"

namespace tetray::render {

struct Box3 {
  Vec3f lo{std::numeric_limits<float>::infinity(), std::numeric_limits<float>::infinity(),
           std::numeric_limits<float>::infinity()};
  Vec3f hi{-std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity(),
           -std::numeric_limits<float>::infinity()};

  void grow(Vec3f p) {
    lo = min(lo, p);
    hi = max(hi, p);
  }
  void grow(const Box3& b) {
    lo = min(lo, b.lo);
    hi = max(hi, b.hi);
  }
  int longest_axis() const {
    const Vec3f e = hi - lo;
    return e.x >= e.y && e.x >= e.z ? 0 : (e.y >= e.z ? 1 : 2);
  }
  // Half the surface area; zero for an empty box.
  float half_area() const {
    if (!(lo.x <= hi.x)) return 0;
    const Vec3f e = hi - lo;
    return e.x * e.y + e.y * e.z + e.z * e.x;
  }
};

inline float half_area(const Bounds4& b) {
  const float ex = b.hi[0] - b.lo[0], ey = b.hi[1] - b.lo[1], ez = b.hi[2] - b.lo[2];
  return ex * ey + ey * ez + ez * ex;
}

}  // namespace tetray::render
