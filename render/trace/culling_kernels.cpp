#include "render/trace/culling_kernels.hpp"

namespace tetray::render {
namespace {

void load(const EyeRelativeTet& q, simd::Float4 (&lanes)[3]) {
  for (int c = 0; c < 3; ++c) lanes[c] = simd::Float4::load_unaligned(q[c]);
}

bool misses_hull(const PacketFrustum& frustum, const EyeRelativeTet& q) {
  simd::Float4 lanes[3];
  load(q, lanes);
  return frustum.misses_hull(lanes);
}

bool outside_depths(const PacketFrustum& frustum, const EyeRelativeTet& q, float tmax_bound) {
  simd::Float4 lanes[3];
  load(q, lanes);
  return frustum.outside_depths(lanes, tmax_bound);
}

bool misses_box(const PacketFrustum& frustum, Vec3f lo, Vec3f hi) {
  return frustum.misses_box(lo, hi);
}

void quad_columns(const std::int32_t* groups, int count, std::int32_t (&columns)[4][16]) {
  static_assert(simd::kWidth <= 16);
  simd::Ints column[4];
  simd::quad_columns(groups, count, column);
  for (int c = 0; c < 4; ++c) column[c].store_unaligned(columns[c]);
}

LeafStraddles* start_frame(std::size_t nodes) { return new LeafStraddles(nodes); }

std::uint64_t leaf_straddles_of(LeafStraddles& frame, std::size_t leaf,
                                std::uint64_t (*find)(void* context), void* context) {
  return frame.of(leaf, [&] { return find(context); });
}

void end_frame(LeafStraddles* frame) { delete frame; }

}  // namespace

// Constant: initialised at load time without running code, before any check of the CPU.
constinit const CullingKernels kCullingKernels = {
    simd::kWidth,     &make_packet_frustum,  &misses_hull,  &outside_depths, &misses_box,
    &straddling_tets, &leaf_straddling_tets, &quad_columns, &start_frame,    &leaf_straddles_of,
    &end_frame};

}  // namespace tetray::render
