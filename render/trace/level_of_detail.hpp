// Level of detail in the traversal (Knoll et al. 2009, §VI, on the tet BVH: docs/architecture.md
// §9). The traversal stops descending at a node that is narrower than `node_pixels` pixel
// footprints at its distance from the eye, and intersects the isosurface of the node's linear
// fit (render/bvh/node_planes.hpp) within the node's box instead of its tets. The test depends
// on the node and the camera only, never on the packet, so neighbouring packets stop at the same
// nodes and no seam opens between them (the paper's reason for its transition slices). Off, the
// policy is NoLod and compiles to nothing.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>

#include "render/bvh/bvh.hpp"
#include "render/bvh/node_planes.hpp"
#include "render/scene/trace_options.hpp"
#include "render/trace/isopolygon.hpp"

namespace tetray::render {

struct NoLod {
  static constexpr bool stops_at(std::uint32_t, const BvhNode&, Vec3f) { return false; }
};

class FootprintLod {
 public:
  // footprint_per_distance: the width of one pixel at unit distance from the eye.
  FootprintLod(const LevelOfDetail& lod, float footprint_per_distance)
      : planes_(lod.planes), allowed_per_distance_(lod.node_pixels * footprint_per_distance) {}

  // The node's widest side against the footprint at the nearest point of its box (zero with the
  // eye inside it, where no node is coarse enough). A node without a surface plane (its field
  // flat) is never stopped at.
  bool stops_at(std::uint32_t index, const BvhNode& node, Vec3f eye) const {
    const Bounds4& b = node.bounds;
    float width = 0, distance2 = 0;
    for (int a = 0; a < 3; ++a) {
      width = std::max(width, b.hi[a] - b.lo[a]);
      const float outside = std::max({b.lo[a] - eye[a], eye[a] - b.hi[a], 0.0f});
      distance2 += outside * outside;
    }
    return width <= allowed_per_distance_ * std::sqrt(distance2) && !planes_[index].flat();
  }

 private:
  std::span<const NodePlane> planes_;
  float allowed_per_distance_;
};

// The isosurface of a node's plane for `iso` within the node's box, as at most two convex
// isopolygons (a plane cuts a box in a polygon of three to six corners); returns their count.
int proxy_isopolygons(const Bounds4& box, const NodePlane& plane, float iso, Isopolygon (&out)[2]);
}  // namespace tetray::render
