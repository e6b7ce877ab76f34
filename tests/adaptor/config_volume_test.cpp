// The volume key of a scene: the transfer function's parts and their defaults, the surfaces
// along the walk; mistakes name the key.
#include <gtest/gtest.h>

#include "adaptor/config/config_parse.hpp"

namespace tetray::config {
namespace {

ParseResult parse(const std::string& scene_lines) {
  return parse_config("scenes:\n  - name: v\n    field: f\n" + scene_lines, "volume.yaml", 1);
}

TEST(ConfigVolume, TransferFunctionAndDefaults) {
  ParseResult r = parse(
      "    volume: {colormap: coolwarm, range: [-1, 2], opacity: [[0, 0], [1, 0.5]],\n"
      "             unit_distance: 0.25, termination: 0.9}\n");
  ASSERT_TRUE(r.error.empty()) << r.error;
  const VolumeSpec& v = *r.config->scenes[0].volume;
  EXPECT_EQ(v.colormap_name, "coolwarm");
  EXPECT_FALSE(v.range.automatic);
  EXPECT_EQ(v.range.hi, 2.0f);
  ASSERT_EQ(v.opacity.size(), 2u);
  EXPECT_EQ(v.opacity[1].opacity, 0.5);
  EXPECT_EQ(v.unit_distance, 0.25);
  EXPECT_EQ(v.termination, 0.9);
  EXPECT_TRUE(r.config->scenes[0].surfaces.empty());
  r = parse("    volume: {opacity: [[0, 1]]}\n");
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_TRUE(r.config->scenes[0].volume->range.automatic);
  EXPECT_EQ(r.config->scenes[0].volume->termination, 1.0);
}

TEST(ConfigVolume, SurfacesOfTheVolumesFieldOrAnother) {
  ParseResult r = parse(
      "    volume: {opacity: [[0, 1]]}\n"
      "    surfaces: {field: interior, isovalues: [0.5, 0.8], colors: [[1, 0, 0], [0, 0, 1]],\n"
      "               opacity: [0.4, 1]}\n");
  ASSERT_TRUE(r.error.empty()) << r.error;
  const Scene& s = r.config->scenes[0];
  EXPECT_EQ(s.volume->surface_field, "interior");
  ASSERT_EQ(s.surfaces.size(), 2u);
  EXPECT_EQ(s.surfaces[0].value, 0.5f);
  EXPECT_EQ(s.surfaces[0].opacity, 0.4f);
  EXPECT_EQ(s.surfaces[1].color.b, 1.0f);
  EXPECT_EQ(s.surfaces[1].opacity, 1.0f);
  // Without a field, or naming the scene's own: the volume's field.
  for (const char* field : {"", "field: f, "}) {
    r = parse("    volume: {opacity: [[0, 1]]}\n    surfaces: {" + std::string(field) +
              "isovalues: [0]}\n");
    ASSERT_TRUE(r.error.empty()) << r.error;
    EXPECT_TRUE(r.config->scenes[0].volume->surface_field.empty());
    EXPECT_EQ(r.config->scenes[0].surfaces.size(), 1u);
  }
}

TEST(ConfigVolume, MistakesNameTheKey) {
  const std::pair<const char*, const char*> cases[] = {
      {"    isovalues: [0]\n    volume: {opacity: [[0, 1]]}\n", "scenes[0].isovalues: not allowed"},
      {"    volume: {}\n", "scenes[0].volume.opacity: missing"},
      {"    volume: {opacity: [[1, 1], [0, 1]]}\n", "values must increase"},
      {"    volume: {opacity: [[0, -1]]}\n", "opacity must lie in"},
      {"    volume: {opacity: [[0, 1]], colormap: jet}\n", "unknown colormap 'jet'"},
      {"    volume: {opacity: [[0, 1]], range: [2, 1]}\n", "needs low < high"},
      {"    volume: {opacity: [[0, 1]], termination: 0.1}\n", "scenes[0].volume.termination"},
      {"    volume: {opacity: [[0, 1]], step: 2}\n", "step"},
      {"    colors: [[1, 1, 1]]\n", "scenes[0].isovalues: missing"},
      {"    volume: {opacity: [[0, 1]]}\n    opacity: [0.5]\n", "scenes[0].opacity: not allowed"},
      {"    volume: {opacity: [[0, 1]]}\n    surfaces: {field: g}\n",
       "scenes[0].surfaces.isovalues: missing"},
      {"    volume: {opacity: [[0, 1]]}\n    surfaces: {isovalues: [0, 1], opacity: [0.5]}\n",
       "scenes[0].surfaces.opacity: give one per isovalue"},
      {"    volume: {opacity: [[0, 1]]}\n    surfaces: {isovalues: [0], colors: [[2, 0, 0]]}\n",
       "scenes[0].surfaces.colors[0]"},
      {"    volume: {opacity: [[0, 1]]}\n    surfaces: {isovalues: [0], max_layers: 2}\n",
       "max_layers"},
      {"    volume: {opacity: [[0, 1]]}\n    surfaces: {isovalues: [0], field: ''}\n",
       "scenes[0].surfaces.field: expected a non-empty string"},
      {"    volume: {opacity: [[0, 1]]}\n    surfaces: [0.5]\n", "scenes[0].surfaces"},
      {"    isovalues: [0]\n    surfaces: {isovalues: [0]}\n", "scenes[0].surfaces: needs volume"},
  };
  for (const auto& [yaml, expected] : cases) {
    const ParseResult r = parse(yaml);
    EXPECT_NE(r.error.find(expected), std::string::npos) << yaml << " gave: " << r.error;
  }
}

}  // namespace
}  // namespace tetray::config
