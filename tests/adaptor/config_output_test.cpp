// The encoding keys of the output map (adaptor/config/config_output.cpp): defaults, every value
// read, and each mistake refused with the file, line and key.
#include <gtest/gtest.h>

#include "adaptor/config/config_output.hpp"
#include "adaptor/config/config_parse.hpp"

namespace tetray::config {
namespace {

constexpr const char* kScene = "scenes: [{name: s, field: f, isovalues: [0]}]\n";

ParseResult parse_output(const std::string& output) {
  return parse_config("output: " + output + "\n" + kScene, "enc.yaml");
}

TEST(ConfigOutput, DefaultsWriteExrAndPngWithoutAMovie) {
  const ParseResult r = parse_config(kScene, "enc.yaml");
  ASSERT_TRUE(r.config) << r.error;
  const Output& o = r.config->output;
  EXPECT_EQ(o.exr_compression, render::ExrCompression::rle);
  EXPECT_EQ(o.png_compression, 1);
  EXPECT_EQ(o.writer_threads, 0);
  EXPECT_FALSE(o.mp4);
  EXPECT_EQ(o.movie.frames_per_second, 24);
  EXPECT_EQ(o.movie.quality, 23);
}

TEST(ConfigOutput, ReadsEveryEncodingKey) {
  const ParseResult r = parse_output(
      "{formats: [png, exr, mp4], exr_compression: piz, png_compression: 12, writer_threads: 3, "
      "movie: {fps: 30, quality: 18}}");
  ASSERT_TRUE(r.config) << r.error;
  const Output& o = r.config->output;
  EXPECT_TRUE(o.png && o.exr && o.mp4);
  EXPECT_EQ(o.exr_compression, render::ExrCompression::piz);
  EXPECT_EQ(o.png_compression, 12);
  EXPECT_EQ(o.writer_threads, 3);
  EXPECT_EQ(o.movie.frames_per_second, 30);
  EXPECT_EQ(o.movie.quality, 18);
  const render::EncodeOptions options = encode_options(o);
  EXPECT_EQ(options.exr_compression, render::ExrCompression::piz);
  EXPECT_EQ(options.png_compression, 12);
}

TEST(ConfigOutput, EveryExrCompressionByName) {
  for (const render::ExrCompressionInfo& c : render::exr_compressions()) {
    const ParseResult r = parse_output("{exr_compression: " + std::string(c.name) + "}");
    ASSERT_TRUE(r.config) << r.error;
    EXPECT_EQ(r.config->output.exr_compression, c.compression);
  }
}

struct Mistake {
  const char* output;
  const char* key;   // in the message
  const char* what;  // in the message
};

class ConfigOutputMistakes : public ::testing::TestWithParam<Mistake> {};

TEST_P(ConfigOutputMistakes, NameFileLineKeyAndProblem) {
  const Mistake& m = GetParam();
  const ParseResult r = parse_output(m.output);
  ASSERT_FALSE(r.config) << m.output;
  EXPECT_NE(r.error.find("enc.yaml:1:"), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(m.key), std::string::npos) << r.error;
  EXPECT_NE(r.error.find(m.what), std::string::npos) << r.error;
}

INSTANTIATE_TEST_SUITE_P(
    Adaptor, ConfigOutputMistakes,
    ::testing::Values(Mistake{"{exr_compression: deflate}", "output.exr_compression",
                              "none, rle, zips, zip"},
                      Mistake{"{exr_compression: [zip]}", "output.exr_compression", ""},
                      Mistake{"{formats: [mp4]}", "output.formats", "mp4 needs exr or png"},
                      Mistake{"{formats: [png, avi]}", "output.formats[1]", "avi"},
                      Mistake{"{png_compression: 13}", "output.png_compression", "13"},
                      Mistake{"{writer_threads: 0}", "output.writer_threads", "0"},
                      Mistake{"{writer_threads: 1025}", "output.writer_threads", "1025"},
                      Mistake{"{movie: {fps: 0}}", "output.movie.fps", "0"},
                      Mistake{"{movie: {fps: 241}}", "output.movie.fps", "241"},
                      Mistake{"{movie: {quality: 52}}", "output.movie.quality", "52"},
                      Mistake{"{movie: {codec: vp9}}", "output.movie", "codec"},
                      Mistake{"{movie: 24}", "output.movie", ""}));

}  // namespace
}  // namespace tetray::config
