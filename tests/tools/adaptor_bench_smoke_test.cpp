// Runs tetray-adaptor-bench on a tiny scene and checks that its JSON has every figure the README
// documents, and that the encoding figures agree with what the formats themselves fix: a stored
// PNG holds at least its raw rows, an uncompressed EXR its 12 bytes per pixel, and each
// compression is marked lossless or lossy as OpenEXR documents it.
#include <gtest/gtest.h>
#include <json/json.h>

#include <filesystem>
#include <set>
#include <string>

#include "support/json_output.hpp"

namespace {

constexpr int kCells = 6, kSide = 64;

Json::Value run_tiny_bench(const std::filesystem::path& dir) {
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return tetray::testing::run_for_json(
      std::string(TETRAY_ADAPTOR_BENCH_EXE) + " -n " + std::to_string(kCells) + " --size " +
          std::to_string(kSide) + " --steps 3 --off-calls 100 --encode-runs 1 --out " +
          (dir / "out").string(),
      "tetray_adaptor_bench_smoke.json");
}

TEST(AdaptorBenchSmoke, JsonHoldsTheWriterAndEncodingFigures) {
  const auto dir = std::filesystem::temp_directory_path() / "tetray_adaptor_bench_smoke";
  const Json::Value root = run_tiny_bench(dir);
  ASSERT_TRUE(root.isObject());
  EXPECT_EQ(root["tets"].asUInt64(), 6u * kCells * kCells * kCells);
  EXPECT_EQ(root["width"].asInt(), kSide);
  EXPECT_TRUE(root["off_trigger_ns"].isNumeric());
  for (const char* run : {"writer_thread", "inline_write"}) {
    for (const char* key : {"blocked_ms", "solver_ms", "refit_trace_ms", "queue_wait_ms",
                            "encode_ms", "write_ms", "check_ms", "overhead_ms"}) {
      EXPECT_TRUE(root[run][key].isNumeric()) << run << "." << key;
    }
  }
  EXPECT_TRUE(root["writer_thread"]["blocked_over_render_percent"].isNumeric());
  EXPECT_GT(root["inline_write"]["encode_ms"].asDouble(), 0.0);

  const std::set<std::string> lossless_exr = {"none", "rle", "zips", "zip", "piz"};
  const std::size_t pixels = std::size_t{kSide} * kSide;
  std::size_t png = 0, exr = 0, mp4 = 0;
  for (const Json::Value& e : root["encoding"]) {
    const std::string format = e["format"].asString();
    const std::string compression = e["compression"].asString();
    EXPECT_GE(e["ms"].asDouble(), 0.0) << format << " " << compression;
    EXPECT_GT(e["bytes"].asUInt64(), 0u) << format << " " << compression;
    if (format == "png") {
      ++png;
      EXPECT_TRUE(e["lossless"].asBool());
      // Stored: every row (a filter byte and 4 bytes a pixel) is in the file.
      if (compression == "level 0") {
        EXPECT_GE(e["bytes"].asUInt64(), kSide * (1 + 4 * kSide));
      }
    } else if (format == "exr") {
      ++exr;
      EXPECT_EQ(e["lossless"].asBool(), lossless_exr.count(compression) == 1) << compression;
      if (compression == "none") {
        EXPECT_GE(e["bytes"].asUInt64(), 12 * pixels);
      }
    } else if (format == "mp4") {
      ++mp4;
      EXPECT_FALSE(e["lossless"].asBool());
    }
  }
  EXPECT_EQ(png, 5u);   // levels 0, 1, 2, 4, 6
  EXPECT_EQ(exr, 10u);  // every compression of OpenEXR 3.1
  EXPECT_EQ(mp4, 1u);
  std::filesystem::remove_all(dir);
}

}  // namespace
