// Runs tetray-bench on a tiny scene and checks that its JSON has the shape of issues 3 and 4.
#include <gtest/gtest.h>
#include <json/json.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace {

Json::Value run_tiny_bench() {
  const auto path = std::filesystem::temp_directory_path() / "tetray_bench_smoke.json";
  std::filesystem::remove(path);
  const std::string command = std::string(TETRAY_BENCH_EXECUTABLE) +
                              " --sizes 6 --size-px 64 --steps 2 --threads 2 --json " +
                              path.string() + " > /dev/null";
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  std::ifstream file(path);
  Json::Value root;
  Json::CharReaderBuilder reader;
  std::string errors;
  EXPECT_TRUE(Json::parseFromStream(reader, file, &root, &errors)) << errors;
  return root;
}

void expect_numbers(const Json::Value& object, std::initializer_list<const char*> keys) {
  for (const char* key : keys)
    EXPECT_TRUE(object.isMember(key) && object[key].isNumeric()) << "missing number: " << key;
}

TEST(BenchSmoke, JsonHasEveryKey) {
  const Json::Value root = run_tiny_bench();
  ASSERT_TRUE(root.isObject());
  EXPECT_TRUE(root["machine"].isObject());
  for (const char* key : {"cpu_model", "simd_target"})
    EXPECT_TRUE(root["machine"][key].isString()) << key;
  EXPECT_TRUE(root["machine"]["cores"].isNumeric());
  EXPECT_EQ(root["threads"].asInt(), 2);
  ASSERT_TRUE(root["scenes"].isArray());
  ASSERT_EQ(root["scenes"].size(), 1u);

  const Json::Value& scene = root["scenes"][0];
  EXPECT_EQ(scene["n"].asInt(), 6);
  EXPECT_EQ(scene["tets"].asUInt64(), 6u * 6 * 6 * 6);
  expect_numbers(scene, {"build_bih_ms", "build_sah_ms", "bvh_bytes_per_tet"});
  for (const char* packet : {"1", "8x8", "16x16", "32x32"}) {
    expect_numbers(scene["trace_ms"], {packet});
    expect_numbers(scene["mrays_per_s"], {packet});
    expect_numbers(scene["counts"][packet],
                   {"packet_box_tests", "ray_box_tests", "isorange_tests", "isopolygon_extractions",
                    "ray_isopolygon_tests", "frustum_culled_isopolygons"});
  }
  expect_numbers(scene["ref"], {"contour_ms", "triangles", "embree_build_ms", "embree_trace_ms",
                                "depth_agree_fraction", "depth_median_rel_diff"});
  expect_numbers(scene["refit"],
                 {"field_only_ms", "geometry_ms", "bound_field_only_ms", "bound_geometry_ms",
                  "rebuild_ms", "step_total_ms", "step_total_default_packet_ms",
                  "ref_step_total_ms", "quality_ratio_after_steps"});
  EXPECT_GT(scene["ref"]["triangles"].asUInt64(), 0u);
  EXPECT_GT(scene["ref"]["depth_agree_fraction"].asDouble(), 0.9);
  // --steps 2: one new step, measured for tetray and for the reference.
  EXPECT_GT(scene["refit"]["step_total_ms"].asDouble(), 0.0);
  EXPECT_GT(scene["refit"]["step_total_default_packet_ms"].asDouble(), 0.0);
  EXPECT_GT(scene["refit"]["ref_step_total_ms"].asDouble(), 0.0);
}

}  // namespace
