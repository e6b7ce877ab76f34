// A packet of S x S primary rays sharing the eye (Wald et al. 2007, §3: 16 x 16 by default), stored
// as structure of arrays for the SIMD kernels, with the interval bounds of its directions (the node
// test of Wald et al. 2007, §5.2 III) and its corner-ray frustum (§4.3, packet_frustum.hpp: the tet
// and isopolygon tests). Rays of a packet that fall off the image repeat a pixel at the edge (so
// the frustum stays tight) and start with tmax = -inf, so they hit nothing.
#pragma once

#include <algorithm>
#include <cstdint>

#include "render/core/framebuffer.hpp"
#include "render/core/simd.hpp"
#include "render/scene/camera.hpp"
#include "render/trace/packet_frustum.hpp"

namespace tetray::render {

// Image rows and columns of points relative to the eye, in the pixel units of a packet or of a
// whole tile: row = row_center - row_scale * dot(p, up) / dot(p, forward), column = column_center
// + column_scale * dot(p, right) / dot(p, forward).
struct RowProjection {
  Vec3f forward, up, right;
  float row_center = 0, row_scale = 0;
  float column_center = 0, column_scale = 0;
  float depth_slack = 0;  // depth_rounding of the frame
};

template <int S>
struct alignas(64) RayPacket {
  static constexpr int kSide = S;
  static constexpr int kRays = S * S;
  using Lanes = simd::LaneTypes<kRays>;
  static constexpr int kLaneWidth = Lanes::width;

  // The rays' order: each lane batch is a block of kBlockRows x kBlockColumns pixels (4 x 4 with
  // 16 lanes, 2 x 4 with 8, 1 x 4 with 4), row by row within the block, the blocks row by row
  // in the packet. A batch then covers a compact patch of the image, so a polygon a few pixels
  // wide meets fewer batches than it would if each batch were a piece of one row. (With 4 lanes,
  // 2 x 2 blocks measured no faster than rows of 4.)
  static constexpr int kBlockColumns = std::min(S, std::min(kLaneWidth, 4));
  static constexpr int kBlockRows = kLaneWidth / kBlockColumns;
  static_assert(S % kBlockColumns == 0 && S % kBlockRows == 0, "blocks tile the packet");

  // The ray of the pixel at (row, column) of the packet.
  static constexpr int index(int row, int column) {
    return ((row / kBlockRows) * (S / kBlockColumns) + column / kBlockColumns) * kLaneWidth +
           (row % kBlockRows) * kBlockColumns + column % kBlockColumns;
  }

  alignas(64) float dx[kRays], dy[kRays], dz[kRays];  // normalized directions
  alignas(64) float ix[kRays], iy[kRays], iz[kRays];  // their inverses
  alignas(64) float tmax[kRays];                      // nearest hit so far
  alignas(64) std::uint32_t key[kRays];               // tie key of that hit
  alignas(64) std::int32_t tet[kRays];                // volume.tets index of that hit, -1: none
  alignas(64) std::int32_t iso[kRays];                // isovalue index of that hit
  alignas(64) float nx[kRays], ny[kRays], nz[kRays];  // unnormalized normal at that hit
  // Per lane batch of rays (kBatches of them): at least the tmax of each of its rays, for the
  // occlusion culling of polygons batch by batch (isopolygon_intersect.hpp), and how many of its
  // rays still have no hit (while any has none, the bound stays infinite).
  static constexpr int kBatches = kRays / kLaneWidth;
  alignas(64) float batch_far[kBatches];
  std::int32_t batch_missing[kBatches];

  Vec3f eye;                   // relative to the volume's origin
  PacketFrustum frustum;       // of the rays in the image
  float inv_lo[3], inv_hi[3];  // interval of the inverse directions, per axis
  bool inv_straddles[3];       // the directions have both signs on this axis
  float tmax_bound = 0;        // >= tmax of every ray (packet occlusion culling)
  int rays_without_hit = 0;    // rays in the image still without a hit: while any is left,
                               // tmax_bound stays infinite and needs no update
  RowProjection projection;    // in packet units: the packet's top-left pixel is row 0, column 0
};

// The frustum of the tile of S x S pixels whose top-left pixel is (x0, y0) (its part in the
// image); `magnitude` bounds the coordinates (relative to the volume's origin) of the eye and
// every vertex (make_packet_frustum).
template <int S>
PacketFrustum tile_frustum(const Camera& camera, const CameraFrame& frame, float magnitude, int x0,
                           int y0) {
  return make_packet_frustum(camera, frame, x0, y0, std::min(x0 + S, camera.width) - 1,
                             std::min(y0 + S, camera.height) - 1, magnitude);
}

// Fills `packet` with the rays of that tile, whose frustum is given (`magnitude` as for it);
// the inverse directions and their interval, which only the traversal's box tests read, are left
// out for a packet that will not traverse (a tile's, tile_trace.cpp).
template <int S, bool kTraverses = true>
void setup_packet(RayPacket<S>& packet, const Camera& camera, const CameraFrame& frame,
                  const PixelDirections& directions, Vec3d origin, const PacketFrustum& frustum,
                  float magnitude, int x0, int y0);

// The image rows and columns of points relative to the eye in the pixel units of the tile whose
// top-left pixel is (x0, y0); `magnitude` as for make_packet_frustum.
RowProjection row_projection(const Camera& camera, const CameraFrame& frame, int x0, int y0,
                             float magnitude);

// Completes a packet whose directions, tmax and eye are set (primary or shadow rays): inverse
// directions, no hits yet, and the interval of the inverse directions.
template <int S>
void prepare_rays(RayPacket<S>& packet);

// The batches' bounds of the packet's tmax as they are now (a packet's rays set anew).
template <int S>
void reset_batch_bounds(RayPacket<S>& packet);

// The largest tmax of the packet's rays (computed once every ray in the image has a hit).
template <int S>
void update_tmax_bound(RayPacket<S>& packet);

}  // namespace tetray::render
