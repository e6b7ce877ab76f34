#include "draw.hpp"

#include <algorithm>

namespace tetray::render {

void blend_pixel(Framebuffer& image, int x, int y, const Ink& ink, float coverage) {
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
  const float a = ink.alpha * coverage;
  if (a <= 0) return;
  float* px = &image.rgba[4 * image.index(x, y)];
  for (int c = 0; c < 3; ++c) px[c] = ink.rgb[c] * a + px[c] * (1 - a);
  px[3] = a + px[3] * (1 - a);
}

void fill_box(Framebuffer& image, const PixelBox& box, const Ink& ink) {
  for (int y = std::max(box.y0, 0); y < std::min(box.y1, image.height); ++y) {
    for (int x = std::max(box.x0, 0); x < std::min(box.x1, image.width); ++x) {
      blend_pixel(image, x, y, ink, 1);
    }
  }
}

void frame_box(Framebuffer& image, const PixelBox& box, int thickness, const Ink& ink) {
  const int t = std::min({thickness, box.width() / 2, box.height() / 2});
  fill_box(image, {box.x0, box.y0, box.x1, box.y0 + t}, ink);
  fill_box(image, {box.x0, box.y1 - t, box.x1, box.y1}, ink);
  fill_box(image, {box.x0, box.y0 + t, box.x0 + t, box.y1 - t}, ink);
  fill_box(image, {box.x1 - t, box.y0 + t, box.x1, box.y1 - t}, ink);
}

PixelBox draw_text(Framebuffer& image, const TextMask& mask, int x, int y, const Ink& ink) {
  for (int row = 0; row < mask.height; ++row) {
    for (int col = 0; col < mask.width; ++col) {
      const std::uint8_t c = mask.at(col, row);
      if (c != 0) blend_pixel(image, x + col, y + row, ink, c / 255.0f);
    }
  }
  return {x, y, x + mask.width, y + mask.height};
}

}  // namespace tetray::render
