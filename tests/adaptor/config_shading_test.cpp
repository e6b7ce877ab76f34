// The scene keys of the shading modalities: shading (smooth | flat), clip (a box and up to six
// planes) and lights, read into config::ShadingSpec; every mistake names the line and the key.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "adaptor/config/config_parse.hpp"

namespace tetray::config {
namespace {

std::string scene_with(const std::string& keys) {
  return "scenes:\n  - name: s\n    field: f\n    isovalues: [0]\n" + keys;
}

TEST(ConfigShading, DefaultsAreFlatAndUnclipped) {
  const ParseResult r = parse_config(scene_with(""), "a.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const ShadingSpec& s = r.config->scenes[0].shading;
  EXPECT_FALSE(s.smooth);
  EXPECT_TRUE(s.clip.empty());
}

TEST(ConfigShading, ReadsSmoothAndTheClipRegion) {
  const ParseResult r =
      parse_config(scene_with("    shading: smooth\n"
                              "    clip:\n"
                              "      box: {min: [-1, -2, -3], max: [0, 2, 3]}\n"
                              "      planes: [{point: [0, 0, 0.5], normal: [0, 0, 2]},\n"
                              "               {point: [1, 1, 1], normal: [1e-300, 1e-300, 0]}]\n"),
                   "a.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const ShadingSpec& s = r.config->scenes[0].shading;
  EXPECT_TRUE(s.smooth);
  ASSERT_TRUE(s.clip.has_box);
  EXPECT_EQ(s.clip.box_lo.z, -3);
  EXPECT_EQ(s.clip.box_hi.y, 2);
  ASSERT_EQ(s.clip.plane_count, 2);
  EXPECT_EQ(s.clip.planes[0].point.z, 0.5);
  EXPECT_DOUBLE_EQ(s.clip.planes[0].normal.z, 1);  // stored as a unit vector
  EXPECT_DOUBLE_EQ(s.clip.planes[1].normal.x, std::sqrt(0.5));
}

TEST(ConfigShading, ReadsTheLights) {
  const ParseResult r = parse_config(
      scene_with("    lights: [{type: headlight},\n"
                 "             {type: point, position: [1, 2, 3], shadows: true, ambient: 0.3},\n"
                 "             {type: directional, direction: [0, -2, 0]}]\n"),
      "a.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const Scene& scene = r.config->scenes[0];
  const render::Lights& lights = scene.shading.lights;
  ASSERT_EQ(lights.count, 3);
  EXPECT_EQ(lights.light[0].kind, render::LightKind::headlight);
  EXPECT_EQ(lights.light[1].kind, render::LightKind::point);
  EXPECT_EQ(lights.light[1].vector.z, 3);
  EXPECT_TRUE(lights.light[1].shadows);
  EXPECT_EQ(lights.light[2].kind, render::LightKind::directional);
  EXPECT_DOUBLE_EQ(lights.light[2].vector.y, -1);  // a unit vector
  EXPECT_FALSE(lights.light[2].shadows);
  EXPECT_EQ(lights.shadow_count(), 1);
  EXPECT_FLOAT_EQ(scene.ambient, 0.3f);
}

TEST(ConfigShading, ReadsTheClipCap) {
  const ParseResult r = parse_config(
      scene_with("    clip:\n"
                 "      planes: [{point: [0, 0, 0], normal: [1, 0, 0]}]\n"
                 "      cap: {field: temperature, colormap: coolwarm, range: [-2, 3]}\n"),
      "a.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const CapSpec& cap = r.config->scenes[0].shading.cap;
  EXPECT_EQ(cap.field, "temperature");
  EXPECT_EQ(cap.colormap_name, "coolwarm");
  EXPECT_FALSE(cap.range.automatic);
  EXPECT_EQ(cap.range.lo, -2);
  EXPECT_EQ(cap.range.hi, 3);
  const ParseResult defaults = parse_config(
      scene_with("    clip: {box: {min: [0, 0, 0], max: [1, 1, 1]}, cap: {field: t}}\n"), "a.yaml");
  ASSERT_TRUE(defaults.config) << defaults.error;
  EXPECT_EQ(defaults.config->scenes[0].shading.cap.colormap_name, "viridis");
  EXPECT_TRUE(defaults.config->scenes[0].shading.cap.range.automatic);
  const ParseResult none = parse_config(scene_with(""), "a.yaml");
  ASSERT_TRUE(none.config) << none.error;
  EXPECT_TRUE(none.config->scenes[0].shading.cap.field.empty());  // no cap by default
}

TEST(ConfigShading, RefusesACapInAVolumeScene) {
  const ParseResult r = parse_config(
      "scenes:\n  - name: v\n    field: f\n    volume: {opacity: [[0, 1]]}\n"
      "    clip: {planes: [{point: [0, 0, 0], normal: [1, 0, 0]}], cap: {field: f}}\n",
      "v.yaml");
  ASSERT_FALSE(r.config);
  EXPECT_NE(r.error.find("v.yaml:5:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("scenes[0].clip.cap"), std::string::npos) << r.error;
}

struct BadKey {
  std::string keys;
  std::string line;  // "a.yaml:<line>:"
  std::string key;   // the key path the message names
};

class ConfigShadingErrors : public testing::TestWithParam<BadKey> {};

TEST_P(ConfigShadingErrors, NameTheLineAndKey) {
  const BadKey& bad = GetParam();
  const ParseResult r = parse_config(scene_with(bad.keys), "a.yaml");
  ASSERT_FALSE(r.config);
  EXPECT_NE(r.error.find(bad.line), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(bad.key), std::string::npos) << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    Keys, ConfigShadingErrors,
    testing::Values(
        BadKey{"    shading: phong\n", "a.yaml:5:", "scenes[0].shading"},
        BadKey{"    clip: {}\n", "a.yaml:5:", "scenes[0].clip"},
        BadKey{"    clip: {sphere: 1}\n", "a.yaml:5:", "scenes[0].clip"},
        BadKey{"    clip: {box: {min: [0, 0, 0]}}\n", "a.yaml:5:", "scenes[0].clip.box.max"},
        BadKey{"    clip: {box: {min: [0, 0, 0], max: [1, 0, 1]}}\n",
               "a.yaml:5:", "scenes[0].clip.box"},
        BadKey{"    clip: {box: {min: [0, 0, 1e13], max: [1, 1, 1]}}\n",
               "a.yaml:5:", "scenes[0].clip.box.min"},
        BadKey{"    clip: {planes: [{point: [0, 0, 0], normal: [0, 0, 0]}]}\n",
               "a.yaml:5:", "scenes[0].clip.planes[0].normal"},
        BadKey{"    clip: {planes: [{normal: [0, 0, 1]}]}\n",
               "a.yaml:5:", "scenes[0].clip.planes[0].point"},
        BadKey{"    clip:\n      planes: [{point: [0, 0, 0], normal: [1, 0, 0]},"
               " {point: [0, 0, 0], normal: [1, 0, 0]}, {point: [0, 0, 0], normal: [1, 0, 0]},"
               " {point: [0, 0, 0], normal: [1, 0, 0]}, {point: [0, 0, 0], normal: [1, 0, 0]},"
               " {point: [0, 0, 0], normal: [1, 0, 0]}, {point: [0, 0, 0], normal: [1, 0, 0]}]\n",
               "a.yaml:6:", "scenes[0].clip.planes"},
        BadKey{"    clip: {cap: {field: t}}\n", "a.yaml:5:", "scenes[0].clip"},
        BadKey{"    clip:\n      planes: [{point: [0, 0, 0], normal: [1, 0, 0]}]\n"
               "      cap: {colormap: viridis}\n",
               "a.yaml:7:", "scenes[0].clip.cap.field"},
        BadKey{"    clip:\n      planes: [{point: [0, 0, 0], normal: [1, 0, 0]}]\n"
               "      cap: {field: t, colormap: jet}\n",
               "a.yaml:7:", "scenes[0].clip.cap.colormap"},
        BadKey{"    clip:\n      planes: [{point: [0, 0, 0], normal: [1, 0, 0]}]\n"
               "      cap: {field: t, range: [2, 1]}\n",
               "a.yaml:7:", "scenes[0].clip.cap.range"},
        BadKey{"    clip:\n      planes: [{point: [0, 0, 0], normal: [1, 0, 0]}]\n"
               "      cap: {field: t, range: sometimes}\n",
               "a.yaml:7:", "scenes[0].clip.cap.range"},
        BadKey{"    clip:\n      planes: [{point: [0, 0, 0], normal: [1, 0, 0]}]\n"
               "      cap: {field: t, opacity: 1}\n",
               "a.yaml:7:", "scenes[0].clip.cap"},
        BadKey{"    clip:\n      planes: [{point: [0, 0, 0], normal: [1, 0, 0]}]\n"
               "      cap: temperature\n",
               "a.yaml:7:", "scenes[0].clip.cap"},
        BadKey{"    lights: []\n", "a.yaml:5:", "scenes[0].lights"},
        BadKey{"    lights: [{type: headlight}, {type: headlight}]\n",
               "a.yaml:5:", "scenes[0].lights[1]"},
        BadKey{"    lights: [{type: point}]\n", "a.yaml:5:", "scenes[0].lights[0].position"},
        BadKey{"    lights: [{type: point, position: [0, 0, 0], direction: [0, 0, 1]}]\n",
               "a.yaml:5:", "scenes[0].lights[0]"},
        BadKey{"    lights: [{type: headlight, shadows: true}]\n",
               "a.yaml:5:", "scenes[0].lights[0]"},
        BadKey{"    lights: [{type: directional, direction: [0, 0, 0]}]\n",
               "a.yaml:5:", "scenes[0].lights[0].direction"},
        BadKey{"    lights: [{type: point, position: [0, 0, 0], shadows: 3}]\n",
               "a.yaml:5:", "scenes[0].lights[0].shadows"},
        BadKey{"    lights: [{ambient: 0.1}, {type: point, position: [0, 0, 1], ambient: 0.2}]\n",
               "a.yaml:5:", "scenes[0].lights[1].ambient"}));

}  // namespace
}  // namespace tetray::config
