#include "run_images.hpp"

#include <algorithm>
#include <limits>
#include <random>

namespace tetray::render::testing {

Framebuffer run_image(int width, int height, std::uint32_t seed, int longest) {
  Framebuffer image(width, height);
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> run_length(1, longest);
  bool active = rng() % 2 == 0;
  for (std::size_t p = 0; p < image.pixel_count(); active = !active) {
    const std::size_t end = std::min(image.pixel_count(), p + run_length(rng));
    for (; p < end; ++p) {
      if (!active) continue;
      const bool far = rng() % 10 == 0;
      image.depth[p] = far ? std::numeric_limits<float>::infinity()
                           : 1.0f + 0.25f * static_cast<float>(rng() % 8);
      image.hit[p] = static_cast<std::uint32_t>(rng() % 1000);
      for (int c = 0; c < 4; ++c) image.rgba[4 * p + c] = static_cast<float>(rng() % 256) / 255.0f;
    }
  }
  return image;
}

bool differs_from_background(const Framebuffer& image, std::size_t p) {
  return image.depth[p] != std::numeric_limits<float>::infinity() || image.hit[p] != kNoHit;
}

}  // namespace tetray::render::testing
