// The packet frustum's tests and the straddle tests as out-of-line entry points with plain-data
// arguments: the traversal only inlines them, so each instruction-set variant has its own copy
// of their code, and this table lets the tests check every copy, not only the one compiled into
// them (tests/render/trace). One table per variant (TraceKernels::culling,
// render/trace/dispatch/trace_kernels.hpp) and one in the baseline library. A SIMD register's
// type differs between variants, so none crosses here: four points relative to the eye are
// floats, component c of point k at [c][k] (the lanes of PacketFrustum's tests).
#pragma once

#include <cstddef>
#include <cstdint>

#include "render/trace/leaf_straddles.hpp"
#include "render/trace/packet_frustum.hpp"
#include "render/trace/tet_straddle.hpp"

namespace tetray::render {

using EyeRelativeTet = float[3][4];

struct CullingKernels {
  int simd_width;  // lanes of this copy's simd::Floats: the most straddling_in_batch takes at once
  decltype(&make_packet_frustum) packet_frustum;
  bool (*misses_hull)(const PacketFrustum& frustum, const EyeRelativeTet& q);
  bool (*outside_depths)(const PacketFrustum& frustum, const EyeRelativeTet& q, float tmax_bound);
  bool (*misses_box)(const PacketFrustum& frustum, Vec3f lo, Vec3f hi);
  decltype(&straddling_tets) straddling_in_batch;
  decltype(&leaf_straddling_tets) straddling_in_leaf;
  // simd::quad_columns, column c into columns[c] (lanes past simd_width left alone).
  void (*quad_columns)(const std::int32_t* groups, int count, std::int32_t (&columns)[4][16]);
  // One frame's LeafStraddles, made, read (find(context) gives a leaf's bits) and ended by this
  // copy: the frame borrows this copy's per-thread storage.
  LeafStraddles* (*start_frame)(std::size_t nodes);
  std::uint64_t (*leaf_straddles_of)(LeafStraddles& frame, std::size_t leaf,
                                     std::uint64_t (*find)(void* context), void* context);
  void (*end_frame)(LeafStraddles* frame);
};

// This library's copy (in a variant, the variant's own).
extern const CullingKernels kCullingKernels;

}  // namespace tetray::render
