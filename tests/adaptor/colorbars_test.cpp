// Colorbars of every colormapped thing of a scene, through the adaptor: a scene colored by a
// field and capped gets two stacked bars (the color field's fixed range, then the cap field's
// automatic range), a volume scene one (its transfer function's colormap and range). Each
// annotated PNG is compared with the bare image of the same run with the expected bars drawn
// over it here, from the ranges the test knows analytically (the box's x runs over [-1, 1]):
// a wrong range moves the ticks and their labels, a wrong colormap or order changes the ramps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "plane_scene.hpp"
#include "render/annotate/annotate.hpp"
#include "render/core/srgb.hpp"
#include "render/scene/colormap.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

constexpr int kWidth = 320, kHeight = 240;
const float kWhite[4] = {1, 1, 1, 1};

// The capped scene: f = z at 0.25 seen head-on, colored by g = x over [-2, 3], cut at
// z = 0.6 with a cap of g over its automatic range; and a volume scene of g.
std::string config(const fs::path& out, const std::string& annotations) {
  const std::string common =
      "    camera: {eye: [0, 0, 5], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
      "    image: {width: 320, height: 240}\n"
      "    background: [1, 1, 1]\n" +
      annotations;
  return "output: {directory: " + out.string() +
         ", formats: [png], quiet: true}\n"
         "scenes:\n"
         "  - name: capped\n"
         "    field: f\n"
         "    isovalues: [0.25]\n"
         "    color_by: g\n"
         "    color_range: [-2, 3]\n"
         "    clip:\n"
         "      planes: [{point: [0, 0, 0.6], normal: [0, 0, 1]}]\n"
         "      cap: {field: g, colormap: coolwarm, range: auto}\n" +
         common +
         "  - name: heat\n"
         "    field: g\n"
         "    volume: {colormap: grayscale, range: auto, opacity: [[-1, 0.2], [1, 2]]}\n" +
         common;
}

render::ColorbarSpec bar(const char* label, const char* colormap, double lo, double hi) {
  render::ColorbarSpec spec{label, lo, hi, {}};
  for (int k = 0; k < 256; ++k) {
    float rgb[3];
    render::find_colormap(colormap)->lookup(static_cast<float>(k) / 255.0f, rgb);
    spec.colors.insert(spec.colors.end(), rgb, rgb + 3);
  }
  return spec;
}

// An opaque PNG in linear light, as the writer held it before encoding (to 8-bit rounding).
render::Framebuffer linear_image(const PngPixels& png) {
  render::Framebuffer image(png.width, png.height);
  for (std::size_t p = 0; p < image.pixel_count(); ++p) {
    for (int c = 0; c < 3; ++c)
      image.rgba[4 * p + c] = static_cast<float>(render::srgb_decode(png.rgba[4 * p + c] / 255.0));
    image.rgba[4 * p + 3] = 1;
  }
  return image;
}

int srgb_level(float linear) {
  const double v = std::clamp(static_cast<double>(linear), 0.0, 1.0);
  const double encoded = v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1 / 2.4) - 0.055;
  return static_cast<int>(std::lround(255 * encoded));
}

struct Comparison {
  std::size_t annotated = 0;  // pixels the bars changed
  std::size_t mismatched = 0;
};

// The bare image with `bars` drawn over it against the annotated one, per channel within one
// 8-bit level (the bare image's own rounding).
Comparison compare(const PngPixels& bare, const PngPixels& annotated,
                   std::vector<render::ColorbarSpec> bars) {
  render::Framebuffer expected = linear_image(bare);
  const render::FontResult font = render::Font::open(render::kDefaultFontPath);
  EXPECT_TRUE(font.font) << font.error;
  render::Annotations a;
  a.font = font.font;
  a.colorbars = std::move(bars);
  render::draw_annotations(expected, a, kWhite);
  Comparison c;
  for (std::size_t p = 0; p < expected.pixel_count(); ++p) {
    bool changed = false, off = false;
    for (int k = 0; k < 3; ++k) {
      const int got = annotated.rgba[4 * p + k];
      changed |= got != bare.rgba[4 * p + k];
      off |= std::abs(got - srgb_level(expected.rgba[4 * p + k])) > 1;
    }
    c.annotated += changed;
    c.mismatched += off;
  }
  return c;
}

class Colorbars : public ::testing::Test {
 protected:
  void run(const fs::path& out, const std::string& annotations) {
    Status status;
    auto adaptor = Adaptor::create_from_yaml(MPI_COMM_WORLD, config(out, annotations), status);
    ASSERT_TRUE(adaptor) << status.message;
    ASSERT_TRUE(adaptor->execute(1, 0.1, scene_.view(), scene_.fields()).ok());
    ASSERT_TRUE(adaptor->finalize().ok());
  }
  static PngPixels image(const fs::path& out, const std::string& scene) {
    return read_png_rgba8((out / scene / (scene + "_000001.png")).string());
  }

  ScratchDir dir_;
  PlaneScene scene_ = make_plane_scene(4);
};

TEST_F(Colorbars, EachColormappedThingGetsItsBar) {
  const fs::path bare = dir_.path() / "bare", on = dir_.path() / "on";
  run(bare, "");
  run(on, "    annotations: {colorbar: true}\n");
  for (const char* scene : {"capped", "heat"}) {
    const PngPixels plain = image(bare, scene), annotated = image(on, scene);
    ASSERT_TRUE(plain.error.empty() && annotated.error.empty()) << plain.error << annotated.error;
    ASSERT_EQ(plain.width, kWidth);
    ASSERT_EQ(annotated.height, kHeight);
  }
  const Comparison capped = compare(image(bare, "capped"), image(on, "capped"),
                                    {bar("g", "viridis", -2, 3), bar("g", "coolwarm", -1, 1)});
  EXPECT_GT(capped.annotated, 500u);
  EXPECT_EQ(capped.mismatched, 0u);
  const Comparison heat =
      compare(image(bare, "heat"), image(on, "heat"), {bar("g", "grayscale", -1, 1)});
  EXPECT_GT(heat.annotated, 250u);
  EXPECT_EQ(heat.mismatched, 0u);
}

TEST_F(Colorbars, ACapAloneIsEnoughForAColorbar) {
  Status status;
  const std::string yaml = plane_config(
      (dir_.path() / "x").string(), "", "",
      "    clip: {planes: [{point: [0, 0, 0.6], normal: [0, 0, 1]}], cap: {field: g}}\n"
      "    annotations: {colorbar: true}\n");
  EXPECT_NE(Adaptor::create_from_yaml(MPI_COMM_WORLD, yaml, status), nullptr) << status.message;
}

}  // namespace
}  // namespace tetray::testing
