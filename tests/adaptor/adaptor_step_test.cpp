// The adaptor end to end on one rank: images, logs and Cinema tables against the analytic plane
// scene, and what a scene does not need it does not do.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

void expect_plane_hits(const std::string& hits) {
  const ExpectedHits expected = expected_plane_hits();
  const auto n = std::stoull(hits);
  EXPECT_GE(n, expected.sure);
  EXPECT_LE(n, expected.sure + expected.edge);
}

TEST(AdaptorStep, WritesImagesLogAndCinemaWithAnalyticCoverage) {
  ScratchDir dir;
  const PlaneScene scene = make_plane_scene(4);
  auto a = make_adaptor(plane_config(dir.path().string(), "", "trigger: {every: 2}\n"));
  ASSERT_TRUE(a);
  for (int step = 0; step < 5; ++step) {
    ExecuteReport report;
    ASSERT_TRUE(run_plane_step(*a, scene, step, {}, &report).ok());
    EXPECT_EQ(report.rendered, step % 2 == 0);
  }
  ASSERT_TRUE(a->finalize().ok());
  for (int step = 0; step < 5; ++step) {
    for (const char* ext : {".png", ".exr"}) {
      const fs::path image = dir.path() / "plane" / ("plane_00000" + std::to_string(step) + ext);
      EXPECT_EQ(fs::exists(image), step % 2 == 0) << image;
    }
  }
  const auto log = read_csv(dir / "tetray_log.csv");
  ASSERT_EQ(log.size(), 4u);  // header + steps 0, 2, 4
  EXPECT_EQ(cell(log, 2, "step"), "2");
  EXPECT_EQ(cell(log, 1, "tets"), std::to_string(scene.mesh.tet_count()));
  EXPECT_EQ(cell(log, 1, "kept_tets"), std::to_string(scene.mesh.tet_count()));
  EXPECT_EQ(cell(log, 1, "rays"), std::to_string(kImageWidth * kImageHeight));
  EXPECT_EQ(cell(log, 1, "composite_ms"), "0.000");  // one rank: no compositing
  for (std::size_t row = 1; row < log.size(); ++row) expect_plane_hits(cell(log, row, "hits"));
  const auto cinema = read_csv(dir / "plane.cdb/data.csv");
  ASSERT_EQ(cinema.size(), 4u);
  EXPECT_EQ(cell(cinema, 3, "FILE"), "../plane/plane_000004.png");
  EXPECT_EQ(cell(cinema, 3, "FILE_exr"), "../plane/plane_000004.exr");
}

TEST(AdaptorStep, WriterThreadAndInlineWritesGiveTheSameFiles) {
  ScratchDir dir;
  const PlaneScene scene = make_plane_scene(4);
  for (const char* depth : {"0", "3"}) {
    auto a = make_adaptor(plane_config(dir / depth, std::string(", writer_queue_depth: ") + depth,
                                       "", "    background: [0.2, 0.3, 0.4]\n"));
    ASSERT_TRUE(a);
    for (int step = 0; step < 4; ++step) ASSERT_TRUE(run_plane_step(*a, scene, step).ok());
    ASSERT_TRUE(a->finalize().ok());
  }
  for (const char* name : {"plane_000003.png", "plane_000003.exr"}) {
    const std::string inline_written = slurp(dir.path() / "0" / "plane" / name);
    EXPECT_FALSE(inline_written.empty());
    EXPECT_EQ(inline_written, slurp(dir.path() / "3" / "plane" / name)) << name;
  }
}

TEST(AdaptorStep, ScenesSkipWhatTheyDoNotNeed) {
  ScratchDir dir;
  const PlaneScene scene = make_plane_scene(20);
  // A second scene on the same field, colored by g; a field no scene names is full of NaN.
  const std::string colored =
      "  - {name: colored, field: f, isovalues: [0.25], color_by: g, image: {width: 32, "
      "height: 32}}\n";
  auto a = make_adaptor(plane_config(dir.path().string()) + colored);
  ASSERT_TRUE(a);
  const std::vector<double> unused(scene.f.size(), std::numeric_limits<double>::quiet_NaN());
  auto fields = scene.fields();
  fields.push_back(FieldView::of("unused", std::span<const double>(unused)));
  const Changes steps[] = {
      {true, true, true}, {false, false, false}, {false, false, true}, {true, false, false}};
  const char* expected[] = {"rebuild", "none", "field_refit", "refit"};
  for (int step = 0; step < 4; ++step) {
    ExecuteReport report;
    const Status s = a->execute(step, step, scene.view(), fields, steps[step], &report);
    ASSERT_TRUE(s.ok()) << s.message;
    EXPECT_EQ(report.bvh_decision, expected[step]) << step;
  }
  ASSERT_TRUE(a->finalize().ok());
  const auto log = read_csv(dir / "tetray_log.csv");
  ASSERT_EQ(log.size(), 9u);
  for (int step = 0; step < 4; ++step) {
    const std::size_t plane_row = 1 + 2 * static_cast<std::size_t>(step);
    EXPECT_EQ(cell(log, plane_row, "scene"), "plane");
    EXPECT_EQ(cell(log, plane_row, "bvh_update"), expected[step]);
    EXPECT_EQ(cell(log, plane_row, "color_ms"), "0.000");
    EXPECT_NE(cell(log, plane_row + 1, "color_ms"), "0.000");
    // The shared volume is updated once, reported by the first scene.
    EXPECT_EQ(cell(log, plane_row + 1, "bvh_ms"), "0.000");
  }
  EXPECT_EQ(cell(log, 3, "bvh_ms"), "0.000");    // nothing changed: no refit
  EXPECT_EQ(cell(log, 3, "check_ms"), "0.000");  // and no validation pass
  expect_plane_hits(cell(log, 1, "hits"));
}

// The BVH's leaves follow what the field's scenes need: 64 tets by default, 16 where a scene
// draws a clip cap (which locates points per pixel in the leaves), and what the config says
// wherever it says. Seen through the log's bvh_bytes: the same leaves give the same bytes.
constexpr const char* kCappedClip =
    "    clip: {planes: [{point: [0, 0, 0.6], normal: [0, 0, 1]}], cap: {field: g}}\n";

TEST(AdaptorStep, ACappedFieldGetsSmallLeavesUnlessTheConfigSetsThem) {
  ScratchDir dir;
  const PlaneScene scene = make_plane_scene(12);
  const std::string cap = kCappedClip;
  const auto bvh_bytes = [&](const std::string& name, const std::string& top_lines,
                             const std::string& scene_lines) {
    auto a = make_adaptor(plane_config(dir / name, "", top_lines, scene_lines));
    EXPECT_TRUE(a);
    if (!a) return std::string();
    EXPECT_TRUE(run_plane_step(*a, scene, 0).ok());
    EXPECT_TRUE(a->finalize().ok());
    return cell(read_csv(dir / (name + "/tetray_log.csv")), 1, "bvh_bytes");
  };
  const std::string leaves_64 = "bvh: {leaf_size: 64}\n", leaves_16 = "bvh: {leaf_size: 16}\n";
  EXPECT_EQ(bvh_bytes("plain", "", ""), bvh_bytes("plain_64", leaves_64, ""));
  const std::string capped = bvh_bytes("capped", "", cap);
  EXPECT_EQ(capped, bvh_bytes("capped_16", leaves_16, cap));
  EXPECT_GT(std::stoull(capped), std::stoull(bvh_bytes("capped_64", leaves_64, cap)));
}

TEST(AdaptorStep, ChangesOnOffTriggerStepsAreNotLost) {
  ScratchDir dir;
  PlaneScene scene = make_plane_scene(4);
  auto a = make_adaptor(plane_config(dir.path().string(), "", "trigger: {every: 2}\n"));
  ASSERT_TRUE(a);
  ASSERT_TRUE(run_plane_step(*a, scene, 0).ok());
  // Move the isosurface out of view on an off step, then render with "nothing changed".
  for (double& f : scene.f) f += 10;
  ASSERT_TRUE(run_plane_step(*a, scene, 1, {false, false, true}).ok());
  ExecuteReport report;
  ASSERT_TRUE(run_plane_step(*a, scene, 2, {false, false, false}, &report).ok());
  EXPECT_EQ(report.bvh_decision, "field_refit");
  ASSERT_TRUE(a->finalize().ok());
  const auto log = read_csv(dir / "tetray_log.csv");
  ASSERT_EQ(log.size(), 3u);
  EXPECT_EQ(cell(log, 2, "hits"), "0");
}

TEST(AdaptorStep, AutoFitCameraAndColormapRender) {
  ScratchDir dir;
  const PlaneScene scene = make_plane_scene(4);
  auto a = make_adaptor(
      "output: {directory: " + dir.path().string() +
      ", quiet: true, formats: [png]}\n"
      "scenes:\n"
      "  - {name: fit, field: f, isovalues: [0.25], color_by: g, colormap: grayscale,\n"
      "     camera: {auto_fit: true, view_direction: [0, 0, 1]},\n"
      "     image: {width: 40, height: 40}}\n");
  ASSERT_TRUE(a);
  ASSERT_TRUE(run_plane_step(*a, scene, 0).ok());
  ASSERT_TRUE(a->finalize().ok());
  const auto log = read_csv(dir / "tetray_log.csv");
  ASSERT_EQ(log.size(), 2u);
  // Looking down z at the fitted box, the square z = 0.25 covers the image's middle.
  const auto hits = std::stoull(cell(log, 1, "hits"));
  EXPECT_GT(hits, 40u * 40u / 8);
  EXPECT_LT(hits, 40u * 40u);
  EXPECT_FALSE(fs::exists(dir.path() / "fit" / "fit_000000.exr"));
  EXPECT_TRUE(fs::exists(dir.path() / "fit" / "fit_000000.png"));
}

}  // namespace
}  // namespace tetray::testing
