#include "render/scene/clip_region.hpp"

#include <cmath>

namespace tetray::render {

LocalClip::LocalClip(const ClipRegion& region, Vec3d origin, float magnitude)
    : has_box(region.has_box), plane_count(std::min(region.plane_count, kMaxClipPlanes)) {
  if (has_box) {
    lo = static_cast<Vec3f>(region.box_lo - origin);
    hi = static_cast<Vec3f>(region.box_hi - origin);
  }
  for (int k = 0; k < plane_count; ++k) {
    const Vec3d n = normalize(region.planes[k].normal);
    normal[k] = static_cast<Vec3f>(n);
    offset[k] = static_cast<float>(dot(n, region.planes[k].point - origin));
  }
  // Far above the rounding of a hit point (a few ulps of the largest coordinate) and of the
  // corner sums above, far below any feature of the image.
  margin = 1e-5f * std::max(magnitude, 1e-30f);
}

}  // namespace tetray::render
