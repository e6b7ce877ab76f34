// The `lod` key through the adaptor: read and checked at creation, and a level-of-detail scene
// follows each new step (the node fits are redone with the refit). The plane scene's isosurface
// is planar, which the node fits represent exactly, so with every node coarse enough the
// level-of-detail image covers the same pixels as the exact one, step after step.
#include <gtest/gtest.h>

#include <string>

#include "adaptor/config/config_parse.hpp"
#include "plane_scene.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"

namespace tetray::testing {
namespace {

std::string scene_with(const std::string& keys) {
  return "scenes:\n  - name: s\n    field: f\n    isovalues: [0]\n" + keys;
}

TEST(ConfigLod, OffByDefaultAndReadWhenGiven) {
  const config::ParseResult off = config::parse_config(scene_with(""), "a.yaml");
  ASSERT_TRUE(off.config) << off.error;
  EXPECT_EQ(off.config->scenes[0].lod_node_pixels, 0);
  const config::ParseResult on =
      config::parse_config(scene_with("    lod: {node_pixels: 2.5}\n"), "a.yaml");
  ASSERT_TRUE(on.config) << on.error;
  EXPECT_EQ(on.config->scenes[0].lod_node_pixels, 2.5f);
}

TEST(ConfigLod, MistakesNameTheKey) {
  const std::pair<std::string, std::string> cases[] = {
      {"    lod: {}\n", "scenes[0].lod.node_pixels: missing"},
      {"    lod: {node_pixels: 0}\n", "scenes[0].lod.node_pixels: must be above 0"},
      {"    lod: {node_pixels: -1}\n", "scenes[0].lod.node_pixels"},
      {"    lod: {node_pixels: 1e9}\n", "scenes[0].lod.node_pixels"},
      {"    lod: {node_pixels: 2, pixel_error: 1}\n", "pixel_error"},
      {"    lod: 3\n", "scenes[0].lod"},
  };
  for (const auto& [keys, expected] : cases) {
    const config::ParseResult r = config::parse_config(scene_with(keys), "a.yaml");
    EXPECT_FALSE(r.config) << keys;
    EXPECT_NE(r.error.find(expected), std::string::npos) << keys << " gave: " << r.error;
    EXPECT_NE(r.error.find("a.yaml"), std::string::npos) << r.error;
  }
  const config::ParseResult volume = config::parse_config(
      "scenes:\n  - name: s\n    field: f\n    volume: {colormap: viridis, opacity: [[0, 0], [1, "
      "1]]}\n    lod: {node_pixels: 2}\n",
      "a.yaml");
  EXPECT_FALSE(volume.config);
  EXPECT_NE(volume.error.find("not to volume scenes"), std::string::npos) << volume.error;
}

// Pixels of the image with any coverage.
std::vector<bool> covered(const std::string& path) {
  const PngPixels png = read_png_rgba8(path);
  EXPECT_TRUE(png.error.empty()) << png.error;
  std::vector<bool> hit(png.rgba.size() / 4);
  for (std::size_t p = 0; p < hit.size(); ++p) hit[p] = png.rgba[4 * p + 3] != 0;
  return hit;
}

TEST(LodScene, FollowsEachNewStep) {
  const ScratchDir exact_dir, lod_dir;
  const auto exact = make_adaptor(plane_config(exact_dir.path().string(), ", formats: [png]"));
  const auto lod = make_adaptor(plane_config(lod_dir.path().string(), ", formats: [png]", "",
                                             "    lod: {node_pixels: 1000}\n"));
  ASSERT_TRUE(exact && lod);
  PlaneScene s = make_plane_scene(8);
  for (std::int64_t step = 1; step <= 2; ++step) {
    // After the first step only the field changes: a refit, not a new load.
    const Changes changes = step == 1 ? Changes{} : Changes{false, false, true};
    ASSERT_TRUE(run_plane_step(*exact, s, step, changes).ok());
    ASSERT_TRUE(run_plane_step(*lod, s, step, changes).ok());
    // The square moves away from the camera: it covers fewer pixels at step 2.
    for (double& value : s.f) value += 0.4;
  }
  ASSERT_TRUE(exact->finalize().ok() && lod->finalize().ok());
  std::size_t previous_hits = 0;
  for (const char* file : {"plane/plane_000001.png", "plane/plane_000002.png"}) {
    const std::vector<bool> a = covered(exact_dir / file), b = covered(lod_dir / file);
    ASSERT_EQ(a.size(), b.size());
    std::size_t hits = 0, differ = 0;
    for (std::size_t p = 0; p < a.size(); ++p) {
      hits += a[p];
      differ += a[p] != b[p];
    }
    EXPECT_GT(hits, 100u) << file;
    EXPECT_LE(differ, hits / 100) << file;  // a ring of edge pixels at most
    EXPECT_NE(hits, previous_hits) << file;
    previous_hits = hits;
  }
}

}  // namespace
}  // namespace tetray::testing
