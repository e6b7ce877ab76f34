// Which tets of a leaf hold a piece of some isosurface, a batch at a time (Wald et al. 2007, §5.2
// V: a tet's own range is tested before anything else about it). Most tets of a leaf hold none; one
// by one, each cost a branch that went either way at random and four scalar loads; here the
// batch's corner indices are moved into lanes, their values gathered, and tested together.
#pragma once

#include <algorithm>
#include <cstdint>

#include "render/core/simd.hpp"
#include "render/scene/iso_set.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// Bit k set when tet first + k straddles an isovalue of `isos`, for k < count <= simd::kWidth.
inline std::uint64_t straddling_tets(const TetVolume& volume, std::uint32_t first, int count,
                                     const IsoSet& isos) {
  using simd::Floats, simd::Ints;
  // Lanes past `count` read vertex 0 (which every volume with tets has) and are dropped below.
  // (Compares and selects for min and max: GCC 12 reports its AVX-512 min and max as reading
  // an uninitialized value.)
  Ints corner[4];
  simd::quad_columns(volume.tets[first].v.data(), count, corner);
  const float* values = &volume.vertices.data()->f;  // a vertex is 4 floats, f the last
  auto corner_values = [&](int c) { return simd::gather(values, corner[c] * 4); };
  Floats lo = corner_values(0), hi = lo;
  for (int c = 1; c < 4; ++c) {
    const Floats f = corner_values(c);
    lo = xsimd::select(f < lo, f, lo);
    hi = xsimd::select(f > hi, f, hi);
  }
  return simd::bits(isos.straddled_by(lo, hi)) & ((std::uint64_t{1} << count) - 1);
}

// Bit k set when tet first + k straddles an isovalue of `isos`, for k < count <= 64 (the tets of
// a leaf, at most kMaxLeafSize), a lane batch at a time.
inline std::uint64_t leaf_straddling_tets(const TetVolume& volume, std::uint32_t first,
                                          std::uint32_t count, const IsoSet& isos) {
  std::uint64_t straddling = 0;
  for (std::uint32_t batch = 0; batch < count; batch += simd::kWidth) {
    const int in_batch = static_cast<int>(std::min<std::uint32_t>(simd::kWidth, count - batch));
    straddling |= straddling_tets(volume, first + batch, in_batch, isos) << batch;
  }
  return straddling;
}

}  // namespace tetray::render
