// The clip region of a scene (render::ClipRegion: a box and planes whose normals point to the part
// cut away) for the reference intersector, in double precision and the volume's local
// coordinates, written from the region's definition without the renderer's float form.
#pragma once

#include <vector>

#include "render/core/vec.hpp"
#include "render/trace/clip_region.hpp"

namespace tetray::test {

using render::Vec3d;

class ReferenceClip {
 public:
  ReferenceClip() = default;  // keeps everything
  ReferenceClip(const render::ClipRegion& region, Vec3d origin);

  bool keeps(Vec3d local_point) const;
  // Distance from the point to the nearest plane of the region (a box face or a clip plane):
  // below float rounding the renderer may decide either way. Infinity without a region.
  double boundary_distance(Vec3d local_point) const;

 private:
  struct Plane {
    Vec3d normal;  // unit, towards the part cut away
    double offset;
  };
  std::vector<Plane> planes_;  // a box is its six faces
};

}  // namespace tetray::test
