// The bounding frustum of a packet of primary rays (Wald et al. 2007, §4.3): the four planes
// through the eye and the packet's corner rays. Primary rays share their origin and fill a
// rectangle of the image, so this frustum is exact up to a small slack, where the
// interval-arithmetic test of Wald et al. 2007, §5.2 III bounds the rays' directions by a box
// (shadow rays have no corner rays: make_direction_frustum bounds their slopes instead). It
// rejects a tet from its four vertices: most tets a packet's traversal reaches lie beside the
// packet, their bounding boxes overlapping its frustum but their hulls not, and each rejection
// saves an isopolygon extraction.
#pragma once

#include <optional>

#include "render/core/simd.hpp"
#include "render/core/vec.hpp"
#include "render/scene/camera.hpp"

namespace tetray::render {

struct PacketFrustum {
  // Planes left, right, bottom, top, in that lane order: a point p is inside plane k when
  // n_k . (p - eye) >= -slack_k, and the frustum is the intersection of the four (which holds
  // nothing behind the eye).
  alignas(16) float nx[4], ny[4], nz[4], slack[4];
  Vec3f forward;            // the view axis, for depth (docs/architecture.md §3)
  float forward_slack = 0;  // rounding bound of a depth computed from eye-relative floats

  // Whether no ray of the packet can meet the convex hull of four points given relative to the
  // eye (component c of point k in lane k of q[c]): all four lie outside one plane.
  bool misses_hull(const simd::Float4 (&q)[3]) const {
    using simd::Float4;
    const Float4 x = q[0], y = q[1], z = q[2];
    for (int k = 0; k < 4; ++k) {
      const Float4 distance = x * nx[k] + y * ny[k] + z * nz[k];
      if (xsimd::all(distance < Float4(-slack[k]))) return true;
    }
    return false;
  }

  // Whether every point of the hull lies behind the eye, or farther than `tmax_bound` along
  // every ray (a ray's distance to a point is at least the point's depth), so no hit there can
  // win.
  bool outside_depths(const simd::Float4 (&q)[3], float tmax_bound) const {
    using simd::Float4;
    const Float4 depth = q[0] * forward.x + q[1] * forward.y + q[2] * forward.z;
    return xsimd::all(depth < Float4(-forward_slack)) ||
           xsimd::all(depth > Float4(tmax_bound * kDepthGrowth + forward_slack));
  }

  // Whether no ray of the packet can meet the box (the volume's, relative to the eye): one plane
  // has the box's farthest corner along its normal outside.
  bool misses_box(Vec3f lo, Vec3f hi) const {
    using simd::Float4;
    const Float4 n[3] = {Float4::load_aligned(nx), Float4::load_aligned(ny),
                         Float4::load_aligned(nz)};
    Float4 farthest(0.0f);
    for (int a = 0; a < 3; ++a) farthest = farthest + xsimd::max(n[a] * lo[a], n[a] * hi[a]);
    return xsimd::any(farthest < -Float4::load_aligned(slack));
  }

 private:
  static constexpr float kDepthGrowth = 1.0f + 0x1p-16f;  // far above a distance's rounding
};

// A bound of the rounding of a view depth, dot(p - eye, forward), computed from eye-relative
// floats whose coordinates `magnitude` bounds (make_packet_frustum's slack).
float depth_rounding(Vec3d forward, float magnitude);

// The frustum of the packet whose rays run through pixel columns [x0, x1] and rows [y0, y1]; the
// tests take points relative to the packet's float eye. `magnitude` bounds the absolute value of
// every coordinate the tests will see (vertices and eye, relative to the volume's origin): the
// slack covers the rounding of points computed from them (isopolygon corners
// leave a tet's hull by an ulp) and of the tests themselves, and each plane also leans out by
// 1/16 pixel plus 1e-5 of its slope against the rounding of the rays' own directions.
PacketFrustum make_packet_frustum(const Camera& camera, const CameraFrame& frame, int x0, int y0,
                                  int x1, int y1, float magnitude);

// The frustum of rays from a shared origin with the given unit directions and no corner rays
// (shadow rays from a point light, Wald et al. 2007, §7): four planes around the axis of their
// mean direction that bound every ray's slopes, with the same slack. None when some ray is more
// than 60 degrees off that axis.
std::optional<PacketFrustum> make_direction_frustum(const float* dx, const float* dy,
                                                    const float* dz, int count, float magnitude);

}  // namespace tetray::render
