// The colorbar of annotate.hpp: a vertical ramp from lo (bottom) to hi (top) at the right edge,
// framed, with ticks and their labels to its right and the field's name above; several share
// the height, one above the other.
#pragma once

#include "annotate.hpp"

namespace tetray::render {

// The look shared by every part of the annotations.
struct TextStyle {
  const Font* font = nullptr;
  int font_px = 0;
  Ink ink;   // the text
  Ink halo;  // around the text
  int halo_px = 1;
};

// The ramp's color for a fraction t in [0, 1] of the way from lo to hi (linear interpolation
// between the spec's samples).
void colorbar_color(const ColorbarSpec& spec, double t, float rgb[3]);

// Draws the colorbar in slice `slot` of `slots` equal horizontal slices of the image and
// records its boxes, ticks and labels in `layout`.
void draw_colorbar(Framebuffer& image, const ColorbarSpec& spec, const TextStyle& style, int slot,
                   int slots, ColorbarLayout& layout);

// A line of text with its halo, its top-left corner at (x, y); the box of the text mask.
PixelBox draw_label(Framebuffer& image, const TextMask& mask, int x, int y, const TextStyle& style);

}  // namespace tetray::render
