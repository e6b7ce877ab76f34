// Image error of an approximate frame against the exact one (the level of detail's error
// against run time): hit/miss disagreement, depth error in pixel footprints, color error.
#pragma once

#include "render/core/framebuffer.hpp"
#include "render/trace/camera.hpp"

namespace tetray::bench {

struct ImageError {
  double hit_miss_fraction = 0;  // pixels where one frame hits and the other misses, of the
                                 // pixels either hits
  double depth_median_px = 0;    // |depth difference| / pixel footprint at the exact depth,
  double depth_p99_px = 0;       // over the pixels both hit
  double color_mean = 0;         // mean |RGBA difference| over all pixels and channels
};

// Both frames from `camera` (the footprint is the pixel's width at the exact hit's depth).
ImageError image_error(const render::Framebuffer& exact, const render::Framebuffer& approximate,
                       const render::Camera& camera);

}  // namespace tetray::bench
