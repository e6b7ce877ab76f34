#include "colorbar.hpp"

#include <algorithm>
#include <cmath>

#include "nice_ticks.hpp"

namespace tetray::render {
namespace {

// The mask grown by `radius` pixels in every direction (a max filter over a square, done as a
// row pass then a column pass), so that a halo of it drawn under the text outlines every glyph.
TextMask dilate(const TextMask& mask, int radius) {
  TextMask out;
  out.width = mask.width + 2 * radius;
  out.height = mask.height + 2 * radius;
  out.pen_x = mask.pen_x + radius;
  out.baseline = mask.baseline + radius;
  const auto at = [&](std::vector<std::uint8_t>& v, int x, int y) -> std::uint8_t& {
    return v[static_cast<std::size_t>(y) * out.width + x];
  };
  std::vector<std::uint8_t> rows(static_cast<std::size_t>(out.width) * out.height, 0);
  for (int y = 0; y < mask.height; ++y) {
    for (int x = 0; x < mask.width; ++x) {
      const std::uint8_t c = mask.at(x, y);
      for (int dx = 0; c != 0 && dx <= 2 * radius; ++dx) {
        at(rows, x + dx, y + radius) = std::max(at(rows, x + dx, y + radius), c);
      }
    }
  }
  out.coverage.assign(rows.size(), 0);
  for (int y = radius; y < radius + mask.height; ++y) {
    for (int x = 0; x < out.width; ++x) {
      const std::uint8_t c = at(rows, x, y);
      for (int dy = -radius; c != 0 && dy <= radius; ++dy) {
        at(out.coverage, x, y + dy) = std::max(at(out.coverage, x, y + dy), c);
      }
    }
  }
  return out;
}

// Where the ramp and its ticks go: centred vertically in its slice of the image under the
// field's name, half the slice tall, its labels ending one margin from the right edge.
PixelBox bar_box(const Framebuffer& image, int font_px, int label_width, int title_height, int slot,
                 int slots) {
  const int margin = static_cast<int>(std::lround(0.75 * font_px));
  const int bar_width = std::max(4, static_cast<int>(std::lround(0.9 * font_px)));
  const int tick = std::max(2, static_cast<int>(std::lround(0.35 * font_px)));
  const int gap = std::max(1, static_cast<int>(std::lround(0.25 * font_px)));
  const int slice = image.height / slots;
  const int height = std::max(2, slice / 2);
  const int top = slot * slice + (slice - height + title_height) / 2;
  const int right = image.width - margin - label_width - gap - tick;
  return {right - bar_width, top, right, top + height};
}

}  // namespace

PixelBox draw_label(Framebuffer& image, const TextMask& mask, int x, int y,
                    const TextStyle& style) {
  const int r = style.halo_px;
  draw_text(image, dilate(mask, r), x - r, y - r, style.halo);
  const PixelBox box = draw_text(image, mask, x, y, style.ink);
  return {box.x0 - r, box.y0 - r, box.x1 + r, box.y1 + r};
}

void colorbar_color(const ColorbarSpec& spec, double t, float rgb[3]) {
  const std::size_t n = spec.colors.size() / 3;
  const double at = std::clamp(t, 0.0, 1.0) * static_cast<double>(n - 1);
  const std::size_t k = std::min(static_cast<std::size_t>(at), n - 2);
  const auto w = static_cast<float>(at - static_cast<double>(k));
  for (int c = 0; c < 3; ++c) {
    rgb[c] = (1 - w) * spec.colors[3 * k + c] + w * spec.colors[3 * (k + 1) + c];
  }
}

void draw_colorbar(Framebuffer& image, const ColorbarSpec& spec, const TextStyle& style, int slot,
                   int slots, ColorbarLayout& layout) {
  const Ticks ticks = nice_ticks(spec.lo, spec.hi);
  std::vector<TextMask> labels;
  int label_width = 0;
  for (double v : ticks.values) {
    labels.push_back(style.font->rasterize(tick_label(v, ticks.step), style.font_px));
    label_width = std::max(label_width, labels.back().width);
  }
  const TextMask name = style.font->rasterize(spec.label, style.font_px);
  const int gap = std::max(1, static_cast<int>(std::lround(0.25 * style.font_px)));
  const PixelBox bar = bar_box(image, style.font_px, label_width, name.height + gap, slot, slots);
  const int line = std::max(1, static_cast<int>(std::lround(style.font_px / 14.0)));
  // The ramp: row j shows the value at its centre, lo at the bottom.
  for (int y = bar.y0; y < bar.y1; ++y) {
    Ink ramp;
    colorbar_color(spec, (bar.y1 - (y + 0.5)) / bar.height(), ramp.rgb);
    fill_box(image, {bar.x0, y, bar.x1, y + 1}, ramp);
  }
  frame_box(image, {bar.x0 - line, bar.y0 - line, bar.x1 + line, bar.y1 + line}, line, style.ink);
  const int right_edge = image.width - static_cast<int>(std::lround(0.75 * style.font_px));
  const int name_x = std::min(bar.x0 - line, right_edge - name.width);
  layout.bar = bar;
  layout.bar_label = draw_label(image, name, name_x, bar.y0 - line - gap - name.height, style);
  const int tick_length = std::max(2, static_cast<int>(std::lround(0.35 * style.font_px)));
  // Digits are about 0.73 em tall above the baseline (DejaVu Sans): centred on the tick.
  const int digit_middle = static_cast<int>(std::lround(0.36 * style.font_px));
  for (std::size_t k = 0; k < ticks.values.size(); ++k) {
    const double t = (ticks.values[k] - spec.lo) / (spec.hi - spec.lo);
    const int row =
        std::clamp(static_cast<int>(std::floor(bar.y1 - t * bar.height())), bar.y0, bar.y1 - 1);
    const int x = bar.x1 + line;
    fill_box(image, {x, row - line / 2, x + tick_length, row - line / 2 + line}, style.ink);
    const TextMask& label = labels[k];
    const int label_x = x + tick_length + gap;
    const int label_y = row - (label.baseline - digit_middle);
    layout.tick_values.push_back(ticks.values[k]);
    layout.tick_rows.push_back(row);
    layout.tick_labels.push_back(draw_label(image, label, label_x, label_y, style));
  }
}

}  // namespace tetray::render
