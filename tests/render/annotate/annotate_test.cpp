// Annotations drawn on blank images and checked against independent facts: the ramp's pixels at
// each tick against the colormap itself (render/trace) at the tick's value, every pixel of ink
// inside one of the boxes the layout reports and each box holding ink where it belongs, a
// changed caption changing only the caption's pixels, sizes doubling with the image, and an
// image left bit-identical when nothing is asked for.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "render/annotate/annotate.hpp"
#include "render/scene/colormap.hpp"

namespace tetray::render {
namespace {

const float kTransparent[4] = {0, 0, 0, 0};

std::shared_ptr<const Font> default_font() {
  const FontResult opened = Font::open(kDefaultFontPath);
  EXPECT_TRUE(opened.font) << opened.error;
  return opened.font;
}

// The colormap sampled as the adaptor hands it over: 256 colors from lo to hi.
ColorbarSpec colorbar_of(const char* colormap, double lo, double hi) {
  ColorbarSpec spec{.label = "temperature", .lo = lo, .hi = hi, .colors = {}};
  const Colormap* map = find_colormap(colormap);
  for (int k = 0; k < 256; ++k) {
    float rgb[3];
    map->lookup(static_cast<float>(k) / 255.0f, rgb);
    spec.colors.insert(spec.colors.end(), rgb, rgb + 3);
  }
  return spec;
}

Annotations full_annotations(double lo = -3.7, double hi = 12.1) {
  return {
      default_font(), "Heat flow", "beam   step 12   t = 0.24", {colorbar_of("viridis", lo, hi)}};
}

bool inked(const Framebuffer& image, int x, int y) {
  return image.rgba[4 * image.index(x, y) + 3] > 0;
}

int ink_in(const Framebuffer& image, const PixelBox& box) {
  int count = 0;
  for (int y = std::max(box.y0, 0); y < std::min(box.y1, image.height); ++y) {
    for (int x = std::max(box.x0, 0); x < std::min(box.x1, image.width); ++x) {
      count += inked(image, x, y);
    }
  }
  return count;
}

// The largest change of a channel per unit of the colormap's parameter.
float steepest_slope(const Colormap& map) {
  const std::size_t stops = map.stops.size() / 3;
  float slope = 0;
  for (std::size_t k = 0; k + 1 < stops; ++k) {
    for (std::size_t c = 0; c < 3; ++c) {
      slope = std::max(slope, std::abs(map.stops[3 * (k + 1) + c] - map.stops[3 * k + c]));
    }
  }
  return slope * static_cast<float>(stops - 1);
}

PixelBox grown(const PixelBox& b, int by) { return {b.x0 - by, b.y0 - by, b.x1 + by, b.y1 + by}; }

// The ramp's pixels at each tick row against the colormap at the tick's value, and its ends.
void expect_ramp_matches(const Framebuffer& image, const ColorbarLayout& bar, const char* name,
                         double lo, double hi) {
  ASSERT_GE(bar.tick_values.size(), 3u);
  ASSERT_LE(bar.tick_values.size(), 7u);
  const int x = (bar.bar.x0 + bar.bar.x1) / 2;
  // A row spans 1/height of the range: the colormap moves by at most its steepest slope times
  // that (the tick's value lies within the row), plus rounding.
  const float tolerance =
      steepest_slope(*find_colormap(name)) / static_cast<float>(bar.bar.height()) + 1e-4f;
  const auto expect_color_at = [&](int y, double value) {
    float want[3];
    find_colormap(name)->lookup(static_cast<float>((value - lo) / (hi - lo)), want);
    const float* got = &image.rgba[4 * image.index(x, y)];
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], tolerance) << "row " << y;
    EXPECT_EQ(got[3], 1.0f);
  };
  for (std::size_t k = 0; k < bar.tick_values.size(); ++k) {
    EXPECT_GE(bar.tick_values[k], lo);  // ticks inside the range the colors use
    EXPECT_LE(bar.tick_values[k], hi);
    expect_color_at(bar.tick_rows[k], bar.tick_values[k]);
  }
  expect_color_at(bar.bar.y1 - 1, lo);  // lo at the bottom
  expect_color_at(bar.bar.y0, hi);      // hi at the top
}

TEST(Annotate, RampMatchesTheColormapAtEveryTick) {
  for (const char* name : {"viridis", "coolwarm", "grayscale"}) {
    SCOPED_TRACE(name);
    Framebuffer image(640, 480);
    const double lo = -3.7, hi = 12.1;
    const Annotations a{default_font(), "", "", {colorbar_of(name, lo, hi)}};
    const AnnotationLayout layout = draw_annotations(image, a, kTransparent);
    ASSERT_EQ(layout.colorbars.size(), 1u);
    expect_ramp_matches(image, layout.colorbars[0], name, lo, hi);
  }
}

// A scene with several colormapped things (a surface colored by a field, a cap) gets one bar
// each, one above the other in order, each with its own colormap, range and ticks.
TEST(Annotate, SeveralColorbarsStackWithTheirOwnRamps) {
  Framebuffer image(800, 800);
  Annotations a{default_font(), "Heat flow", "", {}};
  a.colorbars = {colorbar_of("viridis", -3.7, 12.1), colorbar_of("coolwarm", 0.2, 0.9),
                 colorbar_of("grayscale", 300, 420)};
  const AnnotationLayout layout = draw_annotations(image, a, kTransparent);
  ASSERT_EQ(layout.colorbars.size(), 3u);
  expect_ramp_matches(image, layout.colorbars[0], "viridis", -3.7, 12.1);
  expect_ramp_matches(image, layout.colorbars[1], "coolwarm", 0.2, 0.9);
  expect_ramp_matches(image, layout.colorbars[2], "grayscale", 300, 420);
  EXPECT_LT(layout.title.x1, layout.colorbars[0].bar_label.x0);  // the title at the left
  for (std::size_t k = 0; k < layout.colorbars.size(); ++k) {
    const ColorbarLayout& bar = layout.colorbars[k];
    EXPECT_LE(bar.bar_label.y1, bar.bar.y0);
    EXPECT_GT(bar.bar.x0, 3 * image.width / 4);
    EXPECT_GE(bar.bar.height(), image.height / 8);
    if (k > 0) {
      EXPECT_LT(layout.colorbars[k - 1].bar.y1, bar.bar_label.y0) << k;  // no overlap
    }
  }
  EXPECT_LE(layout.colorbars.back().bar.y1, image.height);
}

TEST(Annotate, TickLabelsSitBesideTheirTicksInOrder) {
  Framebuffer image(800, 600);
  const AnnotationLayout layout = draw_annotations(image, full_annotations(), kTransparent);
  ASSERT_EQ(layout.colorbars.at(0).tick_labels.size(), layout.colorbars.at(0).tick_rows.size());
  for (std::size_t k = 0; k < layout.colorbars.at(0).tick_rows.size(); ++k) {
    const PixelBox& label = layout.colorbars.at(0).tick_labels[k];
    EXPECT_GT(label.x0, layout.colorbars.at(0).bar.x1);
    EXPECT_LE(label.x1, image.width);
    // The digits' ink is centred on the tick's row to within a quarter em.
    int top = label.y1, bottom = label.y0;
    for (int y = label.y0; y < label.y1; ++y) {
      for (int x = label.x0; x < label.x1; ++x) {
        if (image.rgba[4 * image.index(x, y)] == 0 && inked(image, x, y)) {
          top = std::min(top, y);
          bottom = std::max(bottom, y);
        }
      }
    }
    EXPECT_NEAR(0.5 * (top + bottom), layout.colorbars.at(0).tick_rows[k], 0.25 * layout.font_px)
        << k;
    if (k > 0) {
      EXPECT_LT(layout.colorbars.at(0).tick_rows[k],
                layout.colorbars.at(0).tick_rows[k - 1]);  // higher value, higher
    }
  }
}

TEST(Annotate, InkLandsOnlyInTheLayoutsBoxes) {
  Framebuffer image(960, 540);
  const AnnotationLayout layout = draw_annotations(image, full_annotations(), kTransparent);
  // The frame and ticks lie within a line width (at most font_px / 14 + 1) right of the bar.
  const int line = layout.font_px / 14 + 1;
  PixelBox bar_and_ticks = grown(layout.colorbars.at(0).bar, line);
  bar_and_ticks.x1 = layout.colorbars.at(0).tick_labels.front().x0;
  std::vector<PixelBox> boxes{layout.title, layout.caption, layout.colorbars.at(0).bar_label,
                              bar_and_ticks};
  boxes.insert(boxes.end(), layout.colorbars.at(0).tick_labels.begin(),
               layout.colorbars.at(0).tick_labels.end());
  for (const PixelBox& box : boxes) EXPECT_GT(ink_in(image, box), 0);
  int stray = 0;
  for (int y = 0; y < image.height; ++y) {
    for (int x = 0; x < image.width; ++x) {
      const bool boxed = std::any_of(boxes.begin(), boxes.end(),
                                     [&](const PixelBox& b) { return b.contains(x, y); });
      stray += inked(image, x, y) && !boxed;
    }
  }
  EXPECT_EQ(stray, 0);
  // Title above the caption at the top left, the colorbar at the right, nothing overlapping.
  EXPECT_LT(layout.title.x1, image.width / 2);
  EXPECT_LE(layout.title.y1, layout.caption.y0 + 1);
  EXPECT_LT(layout.caption.y1, image.height / 4);
  EXPECT_GT(layout.colorbars.at(0).bar.x0, 3 * image.width / 4);
  EXPECT_LE(layout.colorbars.at(0).bar_label.y1, layout.colorbars.at(0).bar.y0);
}

TEST(Annotate, TextIsAntialiased) {
  Framebuffer image(512, 512);
  draw_annotations(image, {default_font(), "", "step 7", {}}, kTransparent);
  int partial = 0, full = 0;
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    const float a = image.rgba[4 * p + 3];
    partial += a > 0.05f && a < 0.95f;
    full += a >= 0.999f;
  }
  EXPECT_GT(full, 10);
  EXPECT_GT(partial, full / 4);
}

TEST(Annotate, ACaptionChangeChangesOnlyTheCaption) {
  Framebuffer one(640, 480), two(640, 480);
  Annotations a = full_annotations();
  a.caption = "beam   step 1   t = 0.1";
  const AnnotationLayout first = draw_annotations(one, a, kTransparent);
  a.caption = "beam   step 2   t = 0.2";
  const AnnotationLayout second = draw_annotations(two, a, kTransparent);
  int differ = 0, outside = 0;
  for (int y = 0; y < one.height; ++y) {
    for (int x = 0; x < one.width; ++x) {
      const std::size_t p = 4 * one.index(x, y);
      const bool same = std::equal(&one.rgba[p], &one.rgba[p] + 4, &two.rgba[p]);
      differ += !same;
      outside += !same && !first.caption.contains(x, y) && !second.caption.contains(x, y);
    }
  }
  EXPECT_GT(differ, 20);
  EXPECT_EQ(outside, 0);
}

TEST(Annotate, SizesScaleWithTheImage) {
  Framebuffer small(512, 512), large(1024, 1024);
  const AnnotationLayout s = draw_annotations(small, full_annotations(), kTransparent);
  const AnnotationLayout l = draw_annotations(large, full_annotations(), kTransparent);
  EXPECT_EQ(l.font_px, 2 * s.font_px);
  EXPECT_NEAR(l.caption.height(), 2 * s.caption.height(), 3);
  EXPECT_NEAR(l.caption.width(), 2 * s.caption.width(), 0.05 * l.caption.width());
  EXPECT_NEAR(l.colorbars.at(0).bar.height(), 2 * s.colorbars.at(0).bar.height(), 1);
}

TEST(Annotate, NothingAskedLeavesTheImageAsItWas) {
  Framebuffer image(64, 48);
  for (std::size_t k = 0; k < image.rgba.size(); ++k)
    image.rgba[k] = 0.001f * static_cast<float>(k % 997);
  const Framebuffer before = image;
  const float white[4] = {1, 1, 1, 1};
  draw_annotations(image, {}, white);                            // no font
  draw_annotations(image, {default_font(), "", "", {}}, white);  // nothing to draw
  EXPECT_EQ(image.rgba, before.rgba);
}

TEST(Annotate, LightTextOnADarkBackground) {
  const float black[4] = {0, 0, 0, 1};
  Framebuffer image(256, 256);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) image.rgba[4 * p + 3] = 1;
  const AnnotationLayout layout = draw_annotations(image, {default_font(), "", "t", {}}, black);
  float brightest = 0;
  for (int y = layout.caption.y0; y < layout.caption.y1; ++y) {
    for (int x = layout.caption.x0; x < layout.caption.x1; ++x) {
      brightest = std::max(brightest, image.rgba[4 * image.index(x, y)]);
    }
  }
  EXPECT_GT(brightest, 0.99f);
}

TEST(Font, MissingFileIsAnErrorNamingIt) {
  const FontResult opened = Font::open("/no/such/font.ttf");
  EXPECT_FALSE(opened.font);
  EXPECT_NE(opened.error.find("/no/such/font.ttf"), std::string::npos) << opened.error;
}

TEST(Font, Utf8Decoding) {
  EXPECT_EQ(decode_utf8("a\xc3\xa9\xe2\x82\xac"),
            (std::vector<char32_t>{U'a', U'\u00e9', U'\u20ac'}));
  EXPECT_EQ(decode_utf8("\xff"
                        "b\xc3"),
            (std::vector<char32_t>{U'\uFFFD', U'b', U'\uFFFD'}));
}

}  // namespace
}  // namespace tetray::render
