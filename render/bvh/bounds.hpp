// Axis-aligned boxes used while building and refitting the BVH.
#pragma once

#include <limits>

#include "render/bvh/bvh.hpp"
#include "render/core/simd.hpp"
#include "render/core/vec.hpp"

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
};

// A 4D bound being grown, in registers.
struct Bounds4Builder {
  simd::Float4 lo = simd::Float4(std::numeric_limits<float>::infinity());
  simd::Float4 hi = simd::Float4(-std::numeric_limits<float>::infinity());

  void grow(const Vertex& v) {
    const simd::Float4 p = simd::load_float4(v);
    lo = xsimd::min(lo, p);
    hi = xsimd::max(hi, p);
  }
  void grow(const Bounds4& b) {
    lo = xsimd::min(lo, simd::Float4::load_unaligned(b.lo));
    hi = xsimd::max(hi, simd::Float4::load_unaligned(b.hi));
  }
  void grow(const TetVolume& volume, const Tet& tet) {
    for (std::int32_t v : tet.v) grow(volume.vertices[v]);
  }
  // The terms of half the surface area of the box in x, y, z (the SAH's measure): the
  // products of its extents ex ey, ey ez, ez ex in lanes 0 to 2 (lane 3 holds nothing of use),
  // so that sums of areas can be kept in the lanes of a register.
  simd::Float4 area_terms() const {
    const simd::Float4 e = hi - lo;
    return e * xsimd::swizzle(
                   e, xsimd::batch_constant<xsimd::batch<std::uint32_t, simd::Float4::arch_type>, 1,
                                            2, 0, 3>());
  }
  float half_area() const { return simd::sum3(area_terms()); }
  Bounds4 bounds() const {
    Bounds4 b;
    lo.store_unaligned(b.lo);
    hi.store_unaligned(b.hi);
    return b;
  }
};

inline float half_area(const Bounds4& b) {
  Bounds4Builder builder;
  builder.grow(b);
  return builder.half_area();
}

// 4D bounds of one tet.
inline Bounds4 tet_bounds(const TetVolume& volume, const Tet& tet) {
  Bounds4Builder b;
  b.grow(volume, tet);
  return b.bounds();
}

}  // namespace tetray::render
