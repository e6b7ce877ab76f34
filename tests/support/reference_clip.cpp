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

// The region is the intersection of the planes' half-spaces: the ray is inside it over
// [latest entry, earliest exit], and enters through the plane of the latest entry.
std::optional<ReferenceEntry> ReferenceClip::entry(Vec3d eye, Vec3d direction) const {
  if (planes_.empty() || keeps(eye)) return std::nullopt;
  std::vector<double> entries, exits;
  ReferenceEntry best{-std::numeric_limits<double>::infinity(), {}, 0};
  for (const Plane& plane : planes_) {
    const double speed = dot(plane.normal, direction);  // > 0: towards the part cut away
    const double gap = plane.offset - dot(plane.normal, eye);
    if (speed == 0) {
      if (gap < 0) return std::nullopt;
      continue;
    }
    const double t = gap / speed;
    if (speed > 0) {
      exits.push_back(t);
    } else if (gap < 0) {
      entries.push_back(t);
      if (t > best.t) best = {t, plane.normal, 0};
    }
  }
  const double exit = exits.empty() ? std::numeric_limits<double>::infinity()
                                    : *std::min_element(exits.begin(), exits.end());
  if (entries.empty() || best.t > exit) return std::nullopt;
  best.margin = exit - best.t;
  for (double t : entries) {
    if (t != best.t) best.margin = std::min(best.margin, best.t - t);
  }
  return best;
}

}  // namespace tetray::test
