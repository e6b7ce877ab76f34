// Drawing over a composited image (docs/architecture.md §3: linear, premultiplied RGBA): the
// "over" operator with a color of given opacity, per pixel, clipped to the image. Depth and hit
// keys are left alone: annotations are not part of the scene.
#pragma once

#include "font.hpp"
#include "render/core/framebuffer.hpp"

namespace tetray::render {

// A pixel rectangle [x0, x1) x [y0, y1), x the column from the left, y the row from the top.
struct PixelBox {
  int x0 = 0, y0 = 0, x1 = 0, y1 = 0;

  bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
  int width() const { return x1 - x0; }
  int height() const { return y1 - y0; }
};

struct Ink {
  float rgb[3] = {0, 0, 0};  // linear
  float alpha = 1;
};

// Lays `color` with opacity `coverage` x ink.alpha over pixel (x, y); outside the image, nothing.
void blend_pixel(Framebuffer& image, int x, int y, const Ink& ink, float coverage);

void fill_box(Framebuffer& image, const PixelBox& box, const Ink& ink);
// The box's border, `thickness` pixels wide, inside the box.
void frame_box(Framebuffer& image, const PixelBox& box, int thickness, const Ink& ink);

// The mask's top-left corner at (x, y); returns the box the mask covers.
PixelBox draw_text(Framebuffer& image, const TextMask& mask, int x, int y, const Ink& ink);

}  // namespace tetray::render
