// Which hit points need shadow rays (shadow_rays.hpp). Compiled once, not per instruction set:
// a pass over the image, not a trace.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "render/trace/shadow_rays.hpp"

namespace tetray::render {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

}  // namespace

std::vector<float> shadow_ray_depths(const Framebuffer& image,
                                     std::span<const Framebuffer> shadow_terms) {
  std::vector<float> depth(image.pixel_count(), kInf);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, depth.size()), [&](const auto& pixels) {
    for (std::size_t p = pixels.begin(); p != pixels.end(); ++p) {
      const bool lit = std::any_of(shadow_terms.begin(), shadow_terms.end(),
                                   [&](const auto& t) { return term_has_color(&t.rgba[4 * p]); });
      if (lit) depth[p] = image.depth[p];
    }
  });
  return depth;
}

}  // namespace tetray::render
