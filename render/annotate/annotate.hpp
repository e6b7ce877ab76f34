// Annotations of a composited image, drawn on the writer rank just before encoding: an optional
// title and caption (scene, step, simulated time) at the top left and, at the right, a colorbar
// for each colormapped thing of the scene (its field's name and 3-7 nice ticks), stacked from
// the top. Every size is a fraction of the image's, so an
// image twice as large gets text twice as tall.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "draw.hpp"
#include "font.hpp"
#include "render/core/framebuffer.hpp"

namespace tetray::render {

struct ColorbarSpec {
  std::string label;  // the color field's name
  double lo = 0, hi = 1;
  // Linear RGB triplets evenly spaced from the color of lo (first) to that of hi (last); at
  // least two. The colors the surfaces get before shading, so the bar matches a lit surface.
  std::vector<float> colors;
};

struct Annotations {
  std::shared_ptr<const Font> font;     // null: nothing is drawn
  std::string title;                    // empty: none
  std::string caption;                  // empty: none
  std::vector<ColorbarSpec> colorbars;  // top to bottom; each gets an equal slice of the height

  bool empty() const { return !font || (title.empty() && caption.empty() && colorbars.empty()); }
};

// Where one colorbar went.
struct ColorbarLayout {
  PixelBox bar;  // the color ramp itself, inside its frame
  PixelBox bar_label;
  std::vector<double> tick_values;
  std::vector<int> tick_rows;  // the row of each value's color in the ramp
  std::vector<PixelBox> tick_labels;
};

// Where each part went (empty boxes for absent parts): what tests check the ink against.
struct AnnotationLayout {
  int font_px = 0;  // em height of the caption and tick labels
  PixelBox title, caption;
  std::vector<ColorbarLayout> colorbars;  // in the order of Annotations::colorbars
};

// The em height of caption and tick labels for an image of this size.
int annotation_font_px(int width, int height);

// Draws over the image (after its background is put under it). The text is dark on a light or
// transparent background and light on a dark one, with a halo of the other shade so that it
// stays readable over the surfaces. Nothing at all when `annotations.empty()`.
AnnotationLayout draw_annotations(Framebuffer& image, const Annotations& annotations,
                                  const float background[4]);

}  // namespace tetray::render
