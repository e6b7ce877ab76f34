// Movies read back with FFmpeg's own demuxer and decoder: frame count, frame size, what the
// frames show; and the movie under its name only once closed, whole, never one torn or abandoned
// (as by a killed run or a full disk).
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

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

// The files in `dir` other than `kept`: what a writer left beside its movie.
std::vector<std::string> other_files(const ScratchDir& dir, const std::string& kept) {
  std::vector<std::string> names;
  for (const auto& entry : std::filesystem::directory_iterator(dir.path())) {
    const std::string name = entry.path().filename().string();
    if (name != kept) names.push_back(name);
  }
  return names;
}

// A finished movie of `frames` frames at `path`; its bytes.
std::string finished_movie(const std::string& path, int frames) {
  auto movie = create_movie(path, 64, 48);
  if (!movie) return {};
  for (int k = 0; k < frames; ++k) EXPECT_TRUE(movie->append(half_white(64, 48)).ok);
  EXPECT_TRUE(movie->close().ok);
  return testing::slurp(path);
}

// Until close, the movie is a temporary file beside its name (as a killed run would leave it),
// and an earlier movie under the name stays as it was; close puts the new one there.
TEST(Movie, TakesItsNameOnlyWhenClosed) {
  ScratchDir dir;
  const std::string path = dir / "scene.mp4";
  const std::string earlier = finished_movie(path, 2);
  ASSERT_FALSE(earlier.empty());
  auto movie = create_movie(path, 64, 48);
  ASSERT_NE(movie, nullptr);
  for (int k = 0; k < 5; ++k) ASSERT_TRUE(movie->append(half_white(64, 48)).ok);
  EXPECT_EQ(testing::slurp(path), earlier);
  const std::vector<std::string> beside = other_files(dir, "scene.mp4");
  ASSERT_EQ(beside.size(), 1u);
  EXPECT_EQ(beside[0].rfind("scene.mp4.tmp", 0), 0u) << beside[0];
  ASSERT_TRUE(movie->close().ok);
  EXPECT_EQ(decode_movie(path).frames, 5);
  EXPECT_EQ(other_files(dir, "scene.mp4"), std::vector<std::string>{});
}

TEST(Movie, AnAbandonedMovieLeavesTheEarlierOneAndNoFile) {
  ScratchDir dir;
  const std::string path = dir / "scene.mp4";
  const std::string earlier = finished_movie(path, 2);
  auto movie = create_movie(path, 64, 48);
  ASSERT_NE(movie, nullptr);
  for (int k = 0; k < 3; ++k) ASSERT_TRUE(movie->append(half_white(64, 48)).ok);
  movie.reset();
  EXPECT_EQ(testing::slurp(path), earlier);
  EXPECT_EQ(other_files(dir, "scene.mp4"), std::vector<std::string>{});
}

// A full disk (this process's file size limit, SIGXFSZ ignored so that the write fails with
// EFBIG) in the middle of a frame: the movie is not kept, the earlier one stays.
TEST(Movie, AFrameThatCannotBeWrittenLeavesNoMovie) {
  ScratchDir dir;
  const std::string path = dir / "scene.mp4";
  const std::string earlier = finished_movie(path, 2);
  auto movie = create_movie(path, 64, 48);
  ASSERT_NE(movie, nullptr);
  ASSERT_TRUE(movie->append(half_white(64, 48)).ok);
  rlimit saved{};
  ASSERT_EQ(getrlimit(RLIMIT_FSIZE, &saved), 0);
  const sighandler_t previous = signal(SIGXFSZ, SIG_IGN);
  rlimit full = saved;
  full.rlim_cur = std::filesystem::file_size(dir / other_files(dir, "scene.mp4").at(0)) + 10;
  ASSERT_EQ(setrlimit(RLIMIT_FSIZE, &full), 0);
  const WriteResult failed = movie->append(half_white(64, 48));
  setrlimit(RLIMIT_FSIZE, &saved);
  signal(SIGXFSZ, previous);
  EXPECT_FALSE(failed.ok);
  EXPECT_FALSE(movie->append(half_white(64, 48)).ok) << "a torn movie takes no more frames";
  const WriteResult closed = movie->close();
  EXPECT_FALSE(closed.ok);
  EXPECT_NE(closed.message.find(path), std::string::npos) << closed.message;
  EXPECT_EQ(testing::slurp(path), earlier);
  EXPECT_EQ(other_files(dir, "scene.mp4"), std::vector<std::string>{});
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

// A directory under the movie's name could not be replaced at close: refused at create.
TEST(Movie, ADirectoryUnderItsNameIsAnErrorAtCreate) {
  ScratchDir dir;
  const std::string path = dir / "m.mp4";
  std::filesystem::create_directory(path);
  std::string error;
  EXPECT_EQ(MovieWriter::create(path, 32, 32, MovieOptions{}, error), nullptr);
  EXPECT_NE(error.find(path), std::string::npos) << error;
  EXPECT_NE(error.find(std::strerror(EISDIR)), std::string::npos) << error;
  EXPECT_EQ(other_files(dir, "m.mp4"), std::vector<std::string>{});
}

}  // namespace
}  // namespace tetray::render
