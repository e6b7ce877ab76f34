// Colormaps against their published tables (decoded to linear here, independently of the
// implementation), and the interpolation and clamping rules of Colormap::lookup.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>

#include "render/scene/colormap.hpp"

namespace tetray::render {
namespace {

using Color = std::array<double, 3>;

double to_linear(double srgb) {
  return srgb <= 0.04045 ? srgb / 12.92 : std::pow((srgb + 0.055) / 1.055, 2.4);
}

double to_srgb(double linear) {
  return linear <= 0.0031308 ? 12.92 * linear : 1.055 * std::pow(linear, 1.0 / 2.4) - 0.055;
}

Color lookup(const Colormap& map, float s) {
  float rgb[3];
  map.lookup(s, rgb);
  return {rgb[0], rgb[1], rgb[2]};
}

void expect_linear_of(const Colormap& map, float s, Color published_srgb, double tolerance) {
  const Color got = lookup(map, s);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(got[c], to_linear(published_srgb[c]), tolerance) << "s = " << s << " channel " << c;
  }
}

const Colormap& named(const char* name) {
  const Colormap* map = find_colormap(name);
  EXPECT_NE(map, nullptr) << name;
  return *map;
}

TEST(Colormap, KnowsItsNames) {
  for (const char* name : {"viridis", "coolwarm", "grayscale"}) {
    const Colormap* map = find_colormap(name);
    ASSERT_NE(map, nullptr) << name;
    EXPECT_EQ(map->stops.size() % 3, 0u) << name;
    EXPECT_GE(map->stops.size() / 3, 16u) << name;
  }
  EXPECT_EQ(find_colormap("jet"), nullptr);
  EXPECT_EQ(find_colormap(""), nullptr);
  EXPECT_EQ(find_colormap("Viridis"), nullptr);
}

TEST(Colormap, ViridisMatchesThePublishedTable) {
  const Colormap& viridis = named("viridis");
  expect_linear_of(viridis, 0.0f, {0.267004, 0.004874, 0.329415}, 1e-6);
  expect_linear_of(viridis, 1.0f, {0.993248, 0.906157, 0.143936}, 1e-6);
  // Entries of the 256-entry table that are not stops: interpolation error stays small.
  const std::pair<int, Color> entries[] = {{32, {0.278826, 0.175490, 0.483397}},
                                           {64, {0.229739, 0.322361, 0.545706}},
                                           {128, {0.127568, 0.566949, 0.550556}},
                                           {191, {0.360741, 0.785964, 0.387814}}};
  for (const auto& [index, srgb] : entries) {
    const Color got = lookup(viridis, static_cast<float>(index / 255.0));
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(to_srgb(got[c]), srgb[c], 2e-3) << "entry " << index << " channel " << c;
    }
  }
}

TEST(Colormap, ViridisLightnessIncreases) {
  const Colormap& viridis = named("viridis");
  double previous = -1;
  for (int k = 0; k <= 256; ++k) {
    const Color c = lookup(viridis, static_cast<float>(k / 256.0));
    const double luminance = 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2];
    EXPECT_GT(luminance, previous) << "s = " << k / 256.0;
    previous = luminance;
  }
}

TEST(Colormap, CoolWarmMatchesMorelandsTable) {
  const Colormap& coolwarm = named("coolwarm");
  expect_linear_of(coolwarm, 0.0f, {0.2298057, 0.298717966, 0.753683153}, 1e-6);
  expect_linear_of(coolwarm, 0.5f, {0.865395197, 0.86541021, 0.865395561}, 1e-6);
  expect_linear_of(coolwarm, 1.0f, {0.705673158, 0.01555616, 0.150232812}, 1e-6);
  expect_linear_of(coolwarm, 0.25f, {0.552953156, 0.688929332, 0.995375608}, 1e-6);
}

TEST(Colormap, GrayscaleIsGrayAndEvenInSrgb) {
  const Colormap& gray = named("grayscale");
  for (float s : {0.0f, 0.25f, 0.5f, 0.8125f, 1.0f}) {
    const Color c = lookup(gray, s);
    EXPECT_EQ(c[0], c[1]);
    EXPECT_EQ(c[1], c[2]);
    EXPECT_NEAR(to_srgb(c[0]), s, 1e-5) << s;  // these s are stops: exact up to float
  }
}

TEST(Colormap, InterpolatesLinearlyBetweenStops) {
  for (const char* name : {"viridis", "coolwarm", "grayscale"}) {
    const Colormap& map = named(name);
    const std::size_t stops = map.stops.size() / 3;
    for (std::size_t k : {std::size_t{0}, stops / 2, stops - 2}) {
      for (double w : {0.25, 0.5, 0.75}) {
        const auto s = static_cast<float>((double(k) + w) / double(stops - 1));
        const Color got = lookup(map, s);
        for (int c = 0; c < 3; ++c) {
          const double a = map.stops[3 * k + c], b = map.stops[3 * (k + 1) + c];
          EXPECT_NEAR(got[c], a + w * (b - a), 1e-5) << name << " stop " << k << " w " << w;
        }
      }
    }
  }
}

TEST(Colormap, ClampsOutsideTheUnitInterval) {
  const float nan = std::numeric_limits<float>::quiet_NaN();
  const float inf = std::numeric_limits<float>::infinity();
  for (const char* name : {"viridis", "coolwarm", "grayscale"}) {
    const Colormap& map = named(name);
    EXPECT_EQ(lookup(map, -0.5f), lookup(map, 0.0f)) << name;
    EXPECT_EQ(lookup(map, -inf), lookup(map, 0.0f)) << name;
    EXPECT_EQ(lookup(map, 7.0f), lookup(map, 1.0f)) << name;
    EXPECT_EQ(lookup(map, inf), lookup(map, 1.0f)) << name;
    EXPECT_EQ(lookup(map, nan), lookup(map, 0.0f)) << name;
  }
}

}  // namespace
}  // namespace tetray::render
