// 8-bit sRGB codes of the framebuffer's linear, premultiplied color (IEC 61966-2-1), shared by
// the PNG encoder (straight alpha) and the movie (color over black, no alpha).
#pragma once

#include <cstdint>
#include <vector>

#include "render/core/framebuffer.hpp"

namespace tetray::render {

enum class Srgb8Alpha {
  straight,    // RGBA: un-premultiplied color and alpha (PNG)
  over_black,  // RGB: the premultiplied color itself, which is the image over black (video)
};

// Rows `first`..`last` - 1 of `image` into `out` (4 bytes per pixel for straight, 3 for
// over_black), each value clamped to [0, 1] (NaN as 0) and rounded to the nearest code.
void to_srgb8_rows(const Framebuffer& image, int first, int last, Srgb8Alpha alpha,
                   std::uint8_t* out);

// The whole image, rows in parallel (oneTBB, in the caller's arena).
std::vector<std::uint8_t> to_srgb8(const Framebuffer& image, Srgb8Alpha alpha);

}  // namespace tetray::render
