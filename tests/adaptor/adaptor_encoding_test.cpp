// The writer's encoding end to end on one rank: the configured compressions reach the files, the
// writer's thread count changes no byte, a movie per scene holds one frame per image, and a
// movie that cannot be written is an error at the next render step, as an image's is.
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "plane_scene.hpp"
#include "support/movie_read.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

// Steps 0..steps-1 of the plane scene, every one rendered, then finalize.
void run_steps(const std::string& yaml, int steps) {
  const PlaneScene scene = make_plane_scene(4);
  auto a = make_adaptor(yaml);
  ASSERT_TRUE(a);
  for (int step = 0; step < steps; ++step) ASSERT_TRUE(run_plane_step(*a, scene, step).ok());
  const Status finalized = a->finalize();
  ASSERT_TRUE(finalized.ok()) << finalized.message;
}

TEST(AdaptorEncoding, ConfiguredCompressionsReachTheFiles) {
  ScratchDir dir;
  run_steps(plane_config(dir / "piz", ", exr_compression: piz, png_compression: 9"), 2);
  run_steps(plane_config(dir / "default"), 2);
  const std::string image = "plane/plane_000001";
  Imf::InputFile piz((dir / ("piz/" + image + ".exr")).c_str());
  EXPECT_EQ(piz.header().compression(), Imf::PIZ_COMPRESSION);
  Imf::InputFile standard((dir / ("default/" + image + ".exr")).c_str());
  EXPECT_EQ(standard.header().compression(), Imf::RLE_COMPRESSION);
  // Another deflate level, another file, the same pixels.
  const std::string png9 = dir / ("piz/" + image + ".png");
  const std::string png1 = dir / ("default/" + image + ".png");
  EXPECT_NE(slurp(png9), slurp(png1));
  const PngPixels a = read_png_rgba8(png9), b = read_png_rgba8(png1);
  ASSERT_TRUE(a.error.empty() && b.error.empty()) << a.error << b.error;
  EXPECT_EQ(a.rgba, b.rgba);
}

TEST(AdaptorEncoding, WriterThreadsChangeNoByte) {
  ScratchDir dir;
  for (const char* threads : {"1", "3"}) {
    run_steps(plane_config(dir / threads, std::string(", writer_threads: ") + threads), 3);
  }
  for (const char* name : {"plane_000002.png", "plane_000002.exr"}) {
    const std::string one = slurp(dir.path() / "1" / "plane" / name);
    EXPECT_FALSE(one.empty()) << name;
    EXPECT_EQ(one, slurp(dir.path() / "3" / "plane" / name)) << name;
  }
}

TEST(AdaptorEncoding, AMoviePerSceneWithAFramePerImage) {
  ScratchDir dir;
  run_steps(plane_config(dir.path().string(), ", formats: [png, exr, mp4]", "trigger: {every: 2}\n",
                         "    background: [1, 1, 1]\n"),
            9);
  const DecodedMovie movie = decode_movie(dir / "plane/plane_000000.mp4");
  EXPECT_EQ(movie.codec, "h264");
  EXPECT_EQ(movie.frames, 5);  // steps 0, 2, 4, 6, 8
  EXPECT_EQ(movie.width, kImageWidth);
  EXPECT_EQ(movie.height, kImageHeight);
  EXPECT_TRUE(fs::exists(dir / "plane/plane_000008.png"));
}

TEST(AdaptorEncoding, NoMovieUnlessAsked) {
  ScratchDir dir;
  run_steps(plane_config(dir.path().string()), 2);
  EXPECT_FALSE(fs::exists(dir / "plane/plane_000000.mp4"));
}

// A folder where the movie file would go: the movie cannot be created. The images are still
// written, and the error reaches the solver at the next render step, naming the file (written
// inside execute, so that the error is there by the next step).
TEST(AdaptorEncoding, AnUnwritableMovieIsAnErrorAtTheNextStep) {
  ScratchDir dir;
  fs::create_directories(dir / "plane/plane_000000.mp4");
  const PlaneScene scene = make_plane_scene(4);
  auto a = make_adaptor(
      plane_config(dir.path().string(), ", formats: [png, mp4], writer_queue_depth: 0"));
  ASSERT_TRUE(a);
  ASSERT_TRUE(run_plane_step(*a, scene, 0).ok());
  const Status next = run_plane_step(*a, scene, 1);
  EXPECT_EQ(next.code, StatusCode::io_error);
  EXPECT_NE(next.message.find("plane_000000.mp4"), std::string::npos) << next.message;
  EXPECT_TRUE(fs::exists(dir / "plane/plane_000000.png"));
  a->finalize();
}

}  // namespace
}  // namespace tetray::testing
