// RGBA + depth image of docs/architecture.md §3, plus the id of the primitive hit per pixel, which
// makes depth compositing deterministic (ties in depth go to the smaller id).
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "render/core/large_array.hpp"

namespace tetray::render {

// On cache-line boundaries, so that whole pixel rows of a packet can be written with streaming
// stores (frame_pixels.hpp), which need aligned addresses; an image's rows lie on huge pages
// where the system grants them (a tile writes 128 rows of each array).
template <typename T>
using PixelArray = LargeArray<T>;

inline constexpr std::uint32_t kNoHit = std::numeric_limits<std::uint32_t>::max();

struct Framebuffer {
  int width = 0;
  int height = 0;
  PixelArray<float> rgba;         // 4 per pixel, linear, premultiplied; background 0,0,0,0
  PixelArray<float> depth;        // view-axis depth; background +infinity
  PixelArray<std::uint32_t> hit;  // tie-break key of the surface hit (kNoHit: background)

  Framebuffer() = default;
  Framebuffer(int w, int h)
      : width(w),
        height(h),
        rgba(4 * static_cast<std::size_t>(w) * h, 0.0f),
        depth(static_cast<std::size_t>(w) * h, std::numeric_limits<float>::infinity()),
        hit(static_cast<std::size_t>(w) * h, kNoHit) {}

  std::size_t pixel_count() const { return depth.size(); }
  std::size_t index(int i, int j) const { return static_cast<std::size_t>(j) * width + i; }
};

// Whether `image` holds the storage of a width x height image (a moved-from one keeps its sizes
// but not its storage).
inline bool has_shape(const Framebuffer& image, int width, int height) {
  const std::size_t pixels = static_cast<std::size_t>(width) * static_cast<std::size_t>(height);
  return image.width == width && image.height == height && image.pixel_count() == pixels &&
         image.rgba.size() == 4 * pixels && image.hit.size() == pixels;
}

// The depth-compositing rule shared by every compositor and every test: nearer depth wins,
// equal depth goes to the smaller hit key.
inline bool wins_over(float depth_a, std::uint32_t hit_a, float depth_b, std::uint32_t hit_b) {
  return depth_a < depth_b || (depth_a == depth_b && hit_a < hit_b);
}

}  // namespace tetray::render
