#include "render/trace/layer_shading.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <limits>

#include "render/trace/shadow_rays.hpp"
#include "render/trace/trace.hpp"

namespace tetray::render {

void apply_layer_shadows(FragmentImage& color, std::span<const FragmentImage> shadow_terms,
                         int layer, std::span<const std::uint8_t> occluded) {
  // In parallel, as the other per-pixel passes of a frame: each pixel's layer is its own.
  tbb::parallel_for(std::size_t{0}, color.pixel_count(), [&](std::size_t p) {
    if (occluded[p] == 0 || color.begin[p + 1] - color.begin[p] <= std::uint32_t(layer)) return;
    const std::size_t f = color.begin[p] + static_cast<std::size_t>(layer);
    for (std::size_t j = 0; j < shadow_terms.size(); ++j) {
      if (!(occluded[p] & (1u << j))) continue;
      for (int c = 0; c < 3; ++c)
        color.fragments[f].rgba[c] -= shadow_terms[j].fragments[f].rgba[c];
    }
  });
}

void keep_lit_layer_points(std::span<const FragmentImage> shadow_terms, int layer,
                           std::span<float> depth) {
  if (shadow_terms.empty()) return;
  const FragmentImage& first = shadow_terms.front();
  tbb::parallel_for(std::size_t{0}, first.pixel_count(), [&](std::size_t p) {
    if (first.begin[p + 1] - first.begin[p] <= std::uint32_t(layer)) return;
    const std::size_t f = first.begin[p] + static_cast<std::size_t>(layer);
    const bool lit = std::any_of(shadow_terms.begin(), shadow_terms.end(), [&](const auto& t) {
      return term_has_color(t.fragments[f].rgba);
    });
    if (!lit) depth[p] = std::numeric_limits<float>::infinity();
  });
}

// resolve() pixel by pixel in parallel: a megapixel of layers takes a while to sort and blend.
void flatten_layers(FragmentImage& layers, const Camera& camera, Framebuffer& image) {
  // Every pixel is written below, so an image of the right size is reused as it is (allocating
  // a megapixel image each frame cost a third of the blend).
  if (!has_shape(image, layers.width, layers.height))
    image = Framebuffer(layers.width, layers.height);
  tbb::parallel_for(std::size_t{0}, layers.pixel_count(), [&](std::size_t p) {
    const std::span<Fragment> pixel(layers.fragments.data() + layers.begin[p],
                                    layers.fragments.data() + layers.begin[p + 1]);
    merge_pixel(pixel, &image.rgba[4 * p], image.depth[p], image.hit[p]);
  });
  layer_view_depths(layers, camera, 0, image.depth);
}

}  // namespace tetray::render
