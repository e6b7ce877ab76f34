#include "support/reference_clip.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace tetray::test {

ReferenceClip::ReferenceClip(const render::ClipRegion& region, Vec3d origin) {
  const auto add = [&](Vec3d normal, Vec3d point) {
    const Vec3d n = (1 / length(normal)) * normal;
    planes_.push_back({n, dot(n, point - origin)});
  };
  if (region.has_box) {
    for (int a = 0; a < 3; ++a) {
      Vec3d outward{};
      outward[a] = 1;
      add(outward, region.box_hi);
      add(-outward, region.box_lo);
    }
  }
  for (int k = 0; k < region.plane_count; ++k) add(region.planes[k].normal, region.planes[k].point);
}

bool ReferenceClip::keeps(Vec3d p) const {
  return std::all_of(planes_.begin(), planes_.end(),
                     [&](const Plane& plane) { return dot(plane.normal, p) <= plane.offset; });
}

double ReferenceClip::boundary_distance(Vec3d p) const {
  double nearest = std::numeric_limits<double>::infinity();
  for (const Plane& plane : planes_)
    nearest = std::min(nearest, std::abs(dot(plane.normal, p) - plane.offset));
  return nearest;
}

}  // namespace tetray::test
