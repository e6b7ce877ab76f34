// The transparency keys of a scene: opacity (one per isovalue, in [0, 1]) onto the surfaces,
// max_layers (1..16, default 4); every mistake names the file, the line and the key.
#include <gtest/gtest.h>

#include <string>

#include "adaptor/config/config_parse.hpp"

namespace tetray::config {
namespace {

std::string scene_with(const std::string& keys) {
  return "scenes:\n  - name: s\n    field: f\n    isovalues: [0, 0.5, 1]\n" + keys;
}

TEST(ConfigLayers, DefaultsAreOpaqueWithFourLayers) {
  const ParseResult r = parse_config(scene_with(""), "a.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const Scene& s = r.config->scenes[0];
  for (const render::IsoSurface& surface : s.surfaces) EXPECT_EQ(surface.opacity, 1.0f);
  EXPECT_FALSE(render::has_transparency(s.surfaces));
  EXPECT_EQ(s.shading.max_layers, 4);
}

TEST(ConfigLayers, ReadsOpacityPerIsovalueAndMaxLayers) {
  const ParseResult r =
      parse_config(scene_with("    opacity: [1.0, 0.4, 0]\n    max_layers: 16\n"), "a.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const Scene& s = r.config->scenes[0];
  ASSERT_EQ(s.surfaces.size(), 3u);
  EXPECT_EQ(s.surfaces[0].opacity, 1.0f);
  EXPECT_EQ(s.surfaces[1].opacity, 0.4f);
  EXPECT_EQ(s.surfaces[2].opacity, 0.0f);
  EXPECT_TRUE(render::has_transparency(s.surfaces));
  EXPECT_EQ(s.shading.max_layers, 16);
}

struct BadKey {
  std::string keys;
  std::string key;  // the key path the message names
};

class ConfigLayersErrors : public testing::TestWithParam<BadKey> {};

TEST_P(ConfigLayersErrors, NameTheFileLineAndKey) {
  const BadKey& bad = GetParam();
  const ParseResult r = parse_config(scene_with(bad.keys), "a.yaml");
  ASSERT_FALSE(r.config);
  EXPECT_NE(r.error.find("a.yaml:5:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(bad.key), std::string::npos) << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    Keys, ConfigLayersErrors,
    testing::Values(BadKey{"    opacity: [0.5, 0.5]\n", "scenes[0].opacity"},
                    BadKey{"    opacity: [0.5, 0.5, 0.5, 0.5]\n", "scenes[0].opacity"},
                    BadKey{"    opacity: []\n", "scenes[0].opacity"},
                    BadKey{"    opacity: [0.5, 1.5, 0.5]\n", "scenes[0].opacity[1]"},
                    BadKey{"    opacity: [0.5, -0.1, 0.5]\n", "scenes[0].opacity[1]"},
                    BadKey{"    opacity: 0.5\n", "scenes[0].opacity"},
                    BadKey{"    max_layers: 0\n", "scenes[0].max_layers"},
                    BadKey{"    max_layers: 17\n", "scenes[0].max_layers"},
                    BadKey{"    max_layers: 2.5\n", "scenes[0].max_layers"}));

TEST(ConfigLayers, AVolumeSceneTakesNoOpacityList) {
  const ParseResult r = parse_config(
      "scenes:\n  - name: v\n    field: f\n    volume: {colormap: viridis, opacity: [[0, 1], [1, "
      "1]]}\n"
      "    opacity: [0.5]\n",
      "b.yaml");
  ASSERT_FALSE(r.config);
  EXPECT_NE(r.error.find("b.yaml:5:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("scenes[0].opacity"), std::string::npos) << r.error;
}

TEST(ConfigLayers, TransparencyAndAClipCapAreRefusedTogether) {
  const ParseResult capped = parse_config(
      scene_with("    clip: {planes: [{point: [0, 0, 0], normal: [0, 0, 1]}], cap: {field: f}}\n"
                 "    opacity: [1, 1, 1]\n"),
      "c.yaml");
  ASSERT_TRUE(capped.config) << capped.error;  // all opaque: the cap is drawn
  const ParseResult r = parse_config(
      scene_with("    clip: {planes: [{point: [0, 0, 0], normal: [0, 0, 1]}], cap: {field: f}}\n"
                 "    opacity: [1, 0.5, 1]\n"),
      "c.yaml");
  ASSERT_FALSE(r.config);
  EXPECT_NE(r.error.find("scenes[0].opacity"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find("clip.cap"), std::string::npos) << r.error;
}

}  // namespace
}  // namespace tetray::config
