// The clip region of a scene (render::ClipRegion: a box and planes whose normals point to the part
// cut away) for the reference intersector, in double precision and the volume's local
// coordinates, written from the region's definition without the renderer's float form.
#pragma once

#include <optional>
#include <vector>

#include "render/core/vec.hpp"
#include "render/scene/clip_region.hpp"

namespace tetray::test {

using render::Vec3d;

// Where a ray enters the region through one of its planes: the cap point of render/walk/clip_cap.
struct ReferenceEntry {
  double t = 0;  // ray parameter (unit direction)
  Vec3d normal;  // of the plane entered through, towards the part cut away
  // Smallest gap between t and the other planes' crossings that could have decided the entry
  // instead (a ray near an edge of the region): below float rounding either answer is right.
  double margin = 0;
};

class ReferenceClip {
 public:
  ReferenceClip() = default;  // keeps everything
  ReferenceClip(const render::ClipRegion& region, Vec3d origin);

  bool keeps(Vec3d local_point) const;
  // Distance from the point to the nearest plane of the region (a box face or a clip plane):
  // below float rounding the renderer may decide either way. Infinity without a region.
  double boundary_distance(Vec3d local_point) const;
  // The entry of the ray from `eye` (local) along the unit `direction` into the region: empty
  // when the eye is inside it, or the ray misses it.
  std::optional<ReferenceEntry> entry(Vec3d eye, Vec3d direction) const;

 private:
  struct Plane {
    Vec3d normal;  // unit, towards the part cut away
    double offset;
  };
  std::vector<Plane> planes_;  // a box is its six faces
};

}  // namespace tetray::test
