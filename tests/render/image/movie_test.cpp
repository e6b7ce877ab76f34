// Movies read back with FFmpeg's own demuxer and decoder: frame count, frame size, what the
// frames show, and what a writer that never closed its movie (as a killed run) leaves.
#include <gtest/gtest.h>

#include <filesystem>

#include "render/image/movie_writer.hpp"
#include "support/movie_read.hpp"
#include "support/scratch_dir.hpp"

namespace tetray::render {
namespace {

using testing::decode_movie;
using testing::DecodedMovie;
using testing::ScratchDir;

// Left half white, right half black, opaque: linear premultiplied as the tracer writes it.
Framebuffer half_white(int width, int height) {
  Framebuffer image(width, height);
  for (int j = 0; j < height; ++j) {
    for (int i = 0; i < width; ++i) {
      float* px = &image.rgba[4 * (static_cast<std::size_t>(j) * width + i)];
      const float v = i < width / 2 ? 1.0f : 0.0f;
      px[0] = px[1] = px[2] = v;
      px[3] = 1.0f;
    }
  }
  return image;
}

std::unique_ptr<MovieWriter> create_movie(const std::string& path, int width, int height) {
  std::string error;
  auto movie = MovieWriter::create(path, width, height, MovieOptions{}, error);
  EXPECT_NE(movie, nullptr) << error;
  return movie;
}

TEST(Movie, HasAnEncoder) { EXPECT_EQ(movie_codec_name(), "libx264"); }

TEST(Movie, FrameCountSizeAndPictureMatch) {
  ScratchDir dir;
  const std::string path = dir / "scene.mp4";
  auto movie = create_movie(path, 64, 48);
  ASSERT_NE(movie, nullptr);
  const Framebuffer image = half_white(64, 48);
  for (int k = 0; k < 7; ++k) ASSERT_TRUE(movie->append(image).ok);
  EXPECT_EQ(movie->frames(), 7);
  const WriteResult closed = movie->close();
  ASSERT_TRUE(closed.ok) << closed.message;

  const DecodedMovie read = decode_movie(path);
  ASSERT_TRUE(read.error.empty()) << read.error;
  EXPECT_EQ(read.codec, "h264");
  EXPECT_EQ(read.frames, 7);
  EXPECT_EQ(read.width, 64);
  EXPECT_EQ(read.height, 48);
  ASSERT_EQ(read.first_luma.size(), 64u * 48u);
  // Limited-range luma: white 235, black 16; away from the edge, where the codec blurs.
  EXPECT_GT(read.first_luma[24 * 64 + 8], 220);
  EXPECT_LT(read.first_luma[24 * 64 + 56], 30);
}

TEST(Movie, OddSidesArePaddedToEven) {
  ScratchDir dir;
  const std::string path = dir / "odd.mp4";
  auto movie = create_movie(path, 33, 17);
  ASSERT_NE(movie, nullptr);
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(movie->append(half_white(33, 17)).ok);
  ASSERT_TRUE(movie->close().ok);
  const DecodedMovie read = decode_movie(path);
  ASSERT_TRUE(read.error.empty()) << read.error;
  EXPECT_EQ(read.frames, 3);
  EXPECT_EQ(read.width, 34);
  EXPECT_EQ(read.height, 18);
}

// The file as it stands before close() is what a killed run leaves (every frame is flushed to
// the file as its own fragment before append returns): it plays up to the last frame appended.
TEST(Movie, AnUnclosedMoviePlaysUpToItsLastFrame) {
  ScratchDir dir;
  const std::string path = dir / "killed.mp4";
  auto movie = create_movie(path, 64, 64);
  ASSERT_NE(movie, nullptr);
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(movie->append(half_white(64, 64)).ok);
  const std::string copy = dir / "as_left.mp4";
  std::filesystem::copy_file(path, copy);
  const DecodedMovie read = decode_movie(copy);
  ASSERT_TRUE(read.error.empty()) << read.error;
  EXPECT_EQ(read.frames, 5);
  EXPECT_EQ(read.width, 64);
  // A kill in the middle of writing the last fragment: the frames before it still play.
  std::filesystem::resize_file(copy, std::filesystem::file_size(copy) - 40);
  const DecodedMovie torn = decode_movie(copy);
  ASSERT_TRUE(torn.error.empty()) << torn.error;
  EXPECT_EQ(torn.frames, 4);
}

TEST(Movie, RefusesAnotherSizeAndFramesAfterClose) {
  ScratchDir dir;
  auto movie = create_movie(dir / "m.mp4", 32, 32);
  ASSERT_NE(movie, nullptr);
  const WriteResult wrong = movie->append(half_white(32, 30));
  EXPECT_FALSE(wrong.ok);
  EXPECT_NE(wrong.message.find("32x30"), std::string::npos) << wrong.message;
  ASSERT_TRUE(movie->append(half_white(32, 32)).ok);
  ASSERT_TRUE(movie->close().ok);
  EXPECT_FALSE(movie->append(half_white(32, 32)).ok);
  EXPECT_EQ(decode_movie(dir / "m.mp4").frames, 1);
}

TEST(Movie, AnUnwritablePathIsAnErrorNamingIt) {
  ScratchDir dir;
  std::string error;
  const std::string path = dir / "missing/m.mp4";
  EXPECT_EQ(MovieWriter::create(path, 32, 32, MovieOptions{}, error), nullptr);
  EXPECT_NE(error.find(path), std::string::npos) << error;
}

}  // namespace
}  // namespace tetray::render
