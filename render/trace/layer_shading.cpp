#include "render/trace/layer_shading.hpp"

#include <tbb/parallel_for.h>

#include "render/trace/trace.hpp"

namespace tetray::render {

void apply_layer_shadows(FragmentImage& color, std::span<const FragmentImage> shadow_terms,
                         int layer, std::span<const std::uint8_t> occluded) {
  for (std::size_t p = 0; p < color.pixel_count(); ++p) {
    if (occluded[p] == 0 || color.begin[p + 1] - color.begin[p] <= std::uint32_t(layer)) continue;
    const std::size_t f = color.begin[p] + static_cast<std::size_t>(layer);
    for (std::size_t j = 0; j < shadow_terms.size(); ++j) {
      if (!(occluded[p] & (1u << j))) continue;
      for (int c = 0; c < 3; ++c)
        color.fragments[f].rgba[c] -= shadow_terms[j].fragments[f].rgba[c];
    }
  }
}

// resolve() pixel by pixel in parallel: a megapixel of layers takes a while to sort and blend.
Framebuffer flatten_layers(FragmentImage& layers, const Camera& camera) {
  Framebuffer image(layers.width, layers.height);
  tbb::parallel_for(std::size_t{0}, layers.pixel_count(), [&](std::size_t p) {
    const std::span<Fragment> pixel(layers.fragments.data() + layers.begin[p],
                                    layers.fragments.data() + layers.begin[p + 1]);
    merge_pixel(pixel, &image.rgba[4 * p], image.depth[p], image.hit[p]);
  });
  layer_view_depths(layers, camera, 0, image.depth);
  return image;
}

}  // namespace tetray::render
