// Isopolygons (Wald et al. 2007, §4.1): the plane of a linear tet's isosurface bounded by its
// edges, found by the 16-case marching-tetrahedra table. A vertex with f >= iso counts as above
// (docs/architecture.md §3), which makes every case well defined, values equal to the isovalue
// included.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>

#include "render/core/simd.hpp"
#include "render/core/vec.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

struct IsoCase {
  // ends[e][k]: the tet vertex at end e of edge k, the edges in order around the polygon (a
  // triangle's first edge again as the fourth); as 32-bit lanes, to permute the corners with.
  alignas(16) std::int32_t ends[2][4];
  std::int32_t vertex_count;  // 0, 3 or 4
};

// Builds the marching-tetrahedra table: the lone vertex of a 1-3 split gives a triangle of its
// three edges (the first listed again as the fourth); a 2-2 split {a0, a1} | {b0, b1} gives the
// quad a0b0, a0b1, a1b1, a1b0, whose consecutive vertices share a tet face.
constexpr std::array<IsoCase, 16> make_iso_cases() {
  std::array<IsoCase, 16> table{};
  for (int c = 0; c < 16; ++c) {
    int above[4], below[4], na = 0, nb = 0;
    for (int i = 0; i < 4; ++i) {
      if (c & (1 << i)) {
        above[na++] = i;
      } else {
        below[nb++] = i;
      }
    }
    IsoCase& entry = table[c];
    if (na == 0 || nb == 0) continue;
    if (na == 1 || nb == 1) {
      const int lone = na == 1 ? above[0] : below[0];
      const int* others = na == 1 ? below : above;
      entry.vertex_count = 3;
      for (int k = 0; k < 4; ++k) {
        entry.ends[0][k] = lone;
        entry.ends[1][k] = others[k % 3];
      }
      continue;
    }
    entry.vertex_count = 4;
    const int order[4][2] = {
        {above[0], below[0]}, {above[0], below[1]}, {above[1], below[1]}, {above[1], below[0]}};
    for (int k = 0; k < 4; ++k) {
      entry.ends[0][k] = order[k][0];
      entry.ends[1][k] = order[k][1];
    }
  }
  return table;
}

// The table for case = sum of (f_i >= iso) << i.
inline constexpr std::array<IsoCase, 16> kIsoCases = make_iso_cases();

// A tet's four vertices as components: lane k of column c is component c (x, y, z, f) of
// vertex k.
struct TetCorners {
  simd::Float4 column[4];
};

inline TetCorners load_corners(const TetVolume& volume, const Tet& tet) {
  const simd::Float4 rows[4] = {
      simd::load_float4(volume.vertices[tet.v[0]]), simd::load_float4(volume.vertices[tet.v[1]]),
      simd::load_float4(volume.vertices[tet.v[2]]), simd::load_float4(volume.vertices[tet.v[3]])};
  TetCorners corners;
  simd::transpose4(rows, corners.column);
  return corners;
}

// The case of a tet for an isovalue: 0 or 15 when the tet holds none of its surface.
inline int iso_case(const TetCorners& corners, float iso) {
  return simd::bits4(corners.column[3] >= simd::Float4(iso));
}

// Every polygon has four corners: a triangle repeats its first as the fourth (the table lists
// its first edge twice), so the kernels run one branch-free path over four lanes; the repeated
// corner adds an edge of no length, which takes no part in the inside test
// (isopolygon_intersect.hpp).
struct Isopolygon {
  int vertex_count = 0;  // 3 or 4 distinct corners; 0: the tet holds no isosurface
  simd::Float4 xyz[3];   // x, y, z of the corners (corner k in lane k), relative to the
                         // volume's local origin
};

// The points where the isosurface crosses the four edges (a_k, b_k), one per lane. The two ends
// of an edge are ordered by position, then value (not by index), so every tet sharing the edge,
// on any rank, computes bitwise the same point: neighbouring isopolygons meet exactly and the
// surface has no cracks. An end whose value equals the isovalue is returned exactly, so
// polygons meeting at a mesh vertex through different edges meet there too; and the point is
// clamped to the edge's bounding box, which rounding could otherwise leave by an ulp (the BVH
// bounds the vertices, not the polygons). Selects and compares only: the order of random edge
// ends is unpredictable, and a branch on it cost more than the arithmetic.
// The lanes are the four edges of one tet (simd::Float4), or one edge of a batch of tets
// (polygon_block.hpp): the same operations either way, hence the same bits.
template <typename Batch>
inline void edge_crossings(const Batch (&a)[4], const Batch (&b)[4], float iso, Batch (&xyz)[3]) {
  const auto a_first = simd::lexicographic_less<4>(a, b);
  const Batch pf = xsimd::select(a_first, a[3], b[3]), qf = xsimd::select(a_first, b[3], a[3]);
  const Batch value(iso);
  // 0 / 0 only where pf == qf; one end equals the isovalue there and is chosen below.
  const Batch s = (value - pf) / (qf - pf);
  for (int c = 0; c < 3; ++c) {
    const Batch from = xsimd::select(a_first, a[c], b[c]), to = xsimd::select(a_first, b[c], a[c]);
    const Batch along = from + s * (to - from);
    // std::clamp(along, std::min(from, to), std::max(from, to)), with its exact comparisons.
    const Batch lo = xsimd::select(to < from, to, from), hi = xsimd::select(from < to, to, from);
    const Batch above = xsimd::select(along < lo, lo, along);
    const Batch crossing = xsimd::select(hi < above, hi, above);
    xyz[c] = xsimd::select(pf == value, from, xsimd::select(qf == value, to, crossing));
  }
}

// The isopolygon of a tet for an isovalue and its case (iso_case; 0 and 15 give none). The
// edge ends are the corners permuted by the case's lanes.
inline Isopolygon extract_isopolygon(const TetCorners& corners, int case_index, float iso) {
  const IsoCase& entry = kIsoCases[case_index];
  Isopolygon poly;
  poly.vertex_count = entry.vertex_count;
  simd::Float4 a[4], b[4];
  for (int c = 0; c < 4; ++c) {
    a[c] = simd::permute(corners.column[c], entry.ends[0]);
    b[c] = simd::permute(corners.column[c], entry.ends[1]);
  }
  edge_crossings(a, b, iso, poly.xyz);
  return poly;
}

}  // namespace tetray::render
