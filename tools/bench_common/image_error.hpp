// Image error of an approximate frame against a reference frame of the same camera, for the
// benchmarks' error-against-run-time studies (level of detail, volume rendering, the VTK peer):
// hit/miss disagreement, depth error in pixel footprints, color error.
#pragma once

#include "render/core/framebuffer.hpp"
#include "render/scene/camera.hpp"

namespace tetray::bench {

struct ImageError {
  double hit_miss_fraction = 0;  // pixels where one frame hits and the other misses, of the
                                 // pixels either hits
  double depth_median_px = 0;    // |depth difference| / pixel footprint at the reference's depth,
  double depth_p99_px = 0;       // over the pixels both hit
  double color_mean = 0;         // |color difference| over all pixels and the channels compared
  double color_max = 0;
};

// Compares the first `channels` of each pixel's RGBA (3: RGB only). Throws std::runtime_error
// when the frames' sizes differ.
ImageError image_error(const render::Framebuffer& reference, const render::Framebuffer& approximate,
                       const render::Camera& camera, int channels = 4);

}  // namespace tetray::bench
