// Annotations through the adaptor: off (no key, or every part false) writes the same bytes as
// before; on, the caption follows the step and time of a scene that does not change; a colorbar
// without color_by, a missing font and unknown keys fail creation with a message naming them.
#include <gtest/gtest.h>

#include <filesystem>

#include "plane_scene.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

// A color field and a larger image than plane_config's, so that text is more than a few pixels.
std::string config(const fs::path& out, const std::string& annotations) {
  return "output: {directory: " + out.string() +
         ", quiet: true}\n"
         "scenes:\n"
         "  - name: plane\n"
         "    field: f\n"
         "    isovalues: [0.25]\n"
         "    color_by: g\n"
         "    colormap: viridis\n"
         "    color_range: [-1, 1]\n"
         "    camera: {eye: [0, 0, 5], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
         "    image: {width: 320, height: 240}\n" +
         annotations;
}

class Annotations : public ::testing::Test {
 protected:
  // Renders steps 1 and 2 (t = 0.1, 0.2) of the unchanging plane scene into `out`.
  Status run(const fs::path& out, const std::string& annotations) {
    Status status;
    auto adaptor = Adaptor::create_from_yaml(MPI_COMM_WORLD, config(out, annotations), status);
    if (!adaptor) return status;
    for (std::int64_t step : {1, 2}) {
      status =
          adaptor->execute(step, 0.1 * static_cast<double>(step), scene_.view(), scene_.fields());
      if (!status.ok()) return status;
    }
    return adaptor->finalize();
  }

  static std::string image(const fs::path& out, int step, const char* extension = "png") {
    return (out / "plane" / ("plane_00000" + std::to_string(step) + "." + extension)).string();
  }

  Status create_error(const std::string& annotations) {
    Status status;
    auto adaptor =
        Adaptor::create_from_yaml(MPI_COMM_WORLD, config(dir_.path() / "e", annotations), status);
    EXPECT_EQ(adaptor, nullptr);
    return status;
  }

  ScratchDir dir_;
  PlaneScene scene_ = make_plane_scene(2);
};

TEST_F(Annotations, OffWritesTheSameBytes) {
  const fs::path none = dir_.path() / "none", off = dir_.path() / "off";
  ASSERT_TRUE(run(none, "").ok());
  ASSERT_TRUE(run(off, "    annotations: {colorbar: false, time: false}\n").ok());
  for (const char* extension : {"png", "exr"}) {
    EXPECT_EQ(slurp(image(none, 1, extension)), slurp(image(off, 1, extension))) << extension;
  }
  // The scene does not change: without a caption, steps 1 and 2 are the same image.
  EXPECT_EQ(slurp(image(none, 1)), slurp(image(none, 2)));
}

TEST_F(Annotations, CaptionFollowsTheStep) {
  const fs::path plain = dir_.path() / "plain", on = dir_.path() / "on";
  ASSERT_TRUE(run(plain, "").ok());
  const Status status =
      run(on, "    annotations: {colorbar: true, time: true, title: \"Plane\"}\n");
  ASSERT_TRUE(status.ok()) << status.message;
  const PngPixels bare = read_png_rgba8(image(plain, 1));
  const PngPixels one = read_png_rgba8(image(on, 1));
  const PngPixels two = read_png_rgba8(image(on, 2));
  ASSERT_TRUE(bare.error.empty() && one.error.empty() && two.error.empty());
  // Rows the caption and title may cover (the top fifth) differ between the steps; the rest of
  // each annotated image differs from the bare one only where the colorbar is (right quarter).
  std::size_t caption_changes = 0, elsewhere_changes = 0, colorbar_ink = 0, stray_ink = 0;
  for (int y = 0; y < one.height; ++y) {
    for (int x = 0; x < one.width; ++x) {
      const std::size_t p = 4 * (static_cast<std::size_t>(y) * one.width + x);
      const bool steps_differ = !std::equal(&one.rgba[p], &one.rgba[p] + 4, &two.rgba[p]);
      (y < one.height / 5 ? caption_changes : elsewhere_changes) += steps_differ;
      const bool annotated = !std::equal(&one.rgba[p], &one.rgba[p] + 4, &bare.rgba[p]);
      if (annotated && y >= one.height / 5) {
        (x >= 3 * one.width / 4 ? colorbar_ink : stray_ink) += 1;
      }
    }
  }
  EXPECT_GT(caption_changes, 10u);
  EXPECT_EQ(elsewhere_changes, 0u);
  EXPECT_GT(colorbar_ink, 100u);
  EXPECT_EQ(stray_ink, 0u);
}

TEST_F(Annotations, ColorbarNeedsColorBy) {
  Status status;
  const std::string yaml =
      plane_config((dir_.path() / "x").string(), "", "", "    annotations: {colorbar: true}\n");
  EXPECT_EQ(Adaptor::create_from_yaml(MPI_COMM_WORLD, yaml, status), nullptr);
  EXPECT_NE(status.message.find("annotations.colorbar"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("color_by"), std::string::npos) << status.message;
}

TEST_F(Annotations, MissingFontFailsCreation) {
  const Status status = create_error("    annotations: {time: true, font: /no/such/font.ttf}\n");
  EXPECT_NE(status.message.find("annotations.font"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("/no/such/font.ttf"), std::string::npos) << status.message;
}

TEST_F(Annotations, UnknownKeyFailsCreation) {
  const Status status = create_error("    annotations: {colourbar: true}\n");
  EXPECT_NE(status.message.find("colourbar"), std::string::npos) << status.message;
}

}  // namespace
}  // namespace tetray::testing
