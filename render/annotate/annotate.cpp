#include "annotate.hpp"

#include <algorithm>
#include <cmath>

#include "colorbar.hpp"

namespace tetray::render {
namespace {

// Dark text on light or transparent backgrounds (a transparent image is most often shown on
// white), light text on dark ones; the halo is the other shade. 0.18 is mid-grey in linear light.
TextStyle text_style(int width, int height, const float background[4]) {
  const float luminance =
      0.2126f * background[0] + 0.7152f * background[1] + 0.0722f * background[2];
  const bool dark = background[3] > 0.5f && luminance < 0.18f;
  TextStyle style;
  style.font_px = annotation_font_px(width, height);
  const float text = dark ? 1.0f : 0.0f;
  style.ink = {{text, text, text}, 1};
  style.halo = {{1 - text, 1 - text, 1 - text}, 0.75f};
  style.halo_px = std::max(1, static_cast<int>(std::lround(style.font_px / 12.0)));
  return style;
}

}  // namespace

int annotation_font_px(int width, int height) {
  const double side = std::sqrt(static_cast<double>(width) * height);
  return std::clamp(static_cast<int>(std::lround(side / 36)), 8, 400);
}

AnnotationLayout draw_annotations(Framebuffer& image, const Annotations& annotations,
                                  const float background[4]) {
  AnnotationLayout layout;
  if (annotations.empty()) return layout;
  TextStyle style = text_style(image.width, image.height, background);
  style.font = annotations.font.get();
  layout.font_px = style.font_px;
  const int margin = static_cast<int>(std::lround(0.75 * style.font_px));
  int y = margin;
  if (!annotations.title.empty()) {
    const int title_px = static_cast<int>(std::lround(1.3 * style.font_px));
    const TextMask title = style.font->rasterize(annotations.title, title_px);
    layout.title = draw_label(image, title, margin, y, style);
    y += title.height + static_cast<int>(std::lround(0.2 * style.font_px));
  }
  if (!annotations.caption.empty()) {
    const TextMask caption = style.font->rasterize(annotations.caption, style.font_px);
    layout.caption = draw_label(image, caption, margin, y, style);
  }
  const int slots = static_cast<int>(annotations.colorbars.size());
  layout.colorbars.resize(annotations.colorbars.size());
  for (int k = 0; k < slots; ++k)
    draw_colorbar(image, annotations.colorbars[k], style, k, slots, layout.colorbars[k]);
  return layout;
}

}  // namespace tetray::render
