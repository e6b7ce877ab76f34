// Movies read back with FFmpeg's own demuxer and decoder: frame count, frame size, what the
// frames show, and what a writer that never closed its movie (as a killed run) leaves.
extern "C" {
#include <libavcodec/avcodec.h>
#include <libavformat/avformat.h>
}

#include <gtest/gtest.h>

#include <filesystem>

#include "render/image/movie_writer.hpp"
#include "support/scratch_dir.hpp"

namespace tetray::render {
namespace {

using testing::ScratchDir;

struct DecodedMovie {
  std::string error;
  std::string codec;
  int frames = 0;
  int width = 0, height = 0;
  std::vector<std::uint8_t> first_luma;  // the first frame's Y plane, width x height
};

// Every frame of the movie's video stream, decoded.
DecodedMovie decode_movie(const std::string& path) {
  DecodedMovie movie;
  AVFormatContext* format = nullptr;
  if (avformat_open_input(&format, path.c_str(), nullptr, nullptr) < 0) {
    movie.error = "cannot open " + path;
    return movie;
  }
  avformat_find_stream_info(format, nullptr);
  const AVCodec* decoder = nullptr;
  const int stream = av_find_best_stream(format, AVMEDIA_TYPE_VIDEO, -1, -1, &decoder, 0);
  if (stream < 0 || !decoder) {
    movie.error = "no video stream";
    avformat_close_input(&format);
    return movie;
  }
  AVCodecContext* codec = avcodec_alloc_context3(decoder);
  avcodec_parameters_to_context(codec, format->streams[stream]->codecpar);
  avcodec_open2(codec, decoder, nullptr);
  movie.codec = decoder->name;
  AVPacket* packet = av_packet_alloc();
  AVFrame* frame = av_frame_alloc();
  const auto receive = [&] {
    while (avcodec_receive_frame(codec, frame) >= 0) {
      if (movie.frames++ == 0) {
        movie.width = frame->width;
        movie.height = frame->height;
        for (int j = 0; j < frame->height; ++j) {
          const std::uint8_t* row = frame->data[0] + j * frame->linesize[0];
          movie.first_luma.insert(movie.first_luma.end(), row, row + frame->width);
        }
      }
    }
  };
  while (av_read_frame(format, packet) >= 0) {
    if (packet->stream_index == stream) avcodec_send_packet(codec, packet);
    av_packet_unref(packet);
    receive();
  }
  avcodec_send_packet(codec, nullptr);
  receive();
  av_frame_free(&frame);
  av_packet_free(&packet);
  avcodec_free_context(&codec);
  avformat_close_input(&format);
  return movie;
}

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
