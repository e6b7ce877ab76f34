// Runs tetray-bench on a tiny scene and checks that its JSON has every documented key, and that
// its figures agree with what is known of the scene apart from the benchmark: the ray count of the
// image, the hit count of the brute-force reference on the same scene and camera
// (docs/architecture.md §6) and the pixels whose rays meet the mesh's box, and the agreement
// targets with Embree that §6 states.
#include <gtest/gtest.h>
#include <json/json.h>

#include <algorithm>
#include <limits>
#include <string>

#include "support/json_output.hpp"
#include "support/reference_intersector.hpp"
#include "support/render_fixtures.hpp"

namespace {

using tetray::render::Vec3d;

constexpr int kCells = 6, kSide = 64;

Json::Value run_tiny_bench() {
  return tetray::testing::run_for_json(std::string(TETRAY_BENCH_EXECUTABLE) + " --sizes " +
                                           std::to_string(kCells) + " --size-px " +
                                           std::to_string(kSide) + " --steps 2 --threads 2",
                                       "tetray_bench_smoke.json");
}

void expect_numbers(const Json::Value& object, std::initializer_list<const char*> keys) {
  for (const char* key : keys)
    EXPECT_TRUE(object.isMember(key) && object[key].isNumeric()) << "missing number: " << key;
}

void expect_every_key(const Json::Value& root) {
  ASSERT_TRUE(root.isObject());
  EXPECT_TRUE(root["machine"].isObject());
  for (const char* key : {"cpu_model", "simd_target"})
    EXPECT_TRUE(root["machine"][key].isString()) << key;
  EXPECT_TRUE(root["machine"]["cores"].isNumeric());
  EXPECT_EQ(root["threads"].asInt(), 2);
  ASSERT_TRUE(root["scenes"].isArray());
  ASSERT_EQ(root["scenes"].size(), 1u);

  const Json::Value& scene = root["scenes"][0];
  EXPECT_EQ(scene["n"].asInt(), kCells);
  EXPECT_EQ(scene["tets"].asUInt64(), 6u * kCells * kCells * kCells);
  expect_numbers(scene, {"build_bih_ms", "build_sah_ms", "bvh_bytes_per_tet",
                         "volume_bytes_per_tet", "peak_rss_mib"});
  for (const char* packet : {"1", "8x8", "16x16", "32x32"}) {
    expect_numbers(scene["trace_ms"], {packet});
    expect_numbers(scene["mrays_per_s"], {packet});
    expect_numbers(scene["counts"][packet],
                   {"packet_box_tests", "ray_box_tests", "isorange_tests", "isopolygon_extractions",
                    "ray_isopolygon_tests", "frustum_culled_isopolygons"});
  }
  expect_numbers(scene["ref"], {"contour_ms", "triangles", "embree_build_ms", "embree_trace_ms",
                                "embree_step_build_ms", "embree_step_trace_ms",
                                "depth_agree_fraction", "depth_median_rel_diff"});
  // Embree's build for a new step (dynamic scene, low quality) traces the default build's depth
  // image: bitwise where measured, here at most 0.1% of the pixels (a wrong scene or trace
  // differs on many).
  expect_numbers(scene["ref"], {"embree_step_depth_differs"});
  EXPECT_LE(scene["ref"]["embree_step_depth_differs"].asUInt64(), kSide * kSide / 1000u);
  expect_numbers(scene["ref"]["trace_in_turn"], {"rounds", "tetray_ms", "embree_ms"});
  EXPECT_GT(scene["ref"]["trace_in_turn"]["tetray_ms"].asDouble(), 0.0);
  EXPECT_GT(scene["ref"]["trace_in_turn"]["embree_ms"].asDouble(), 0.0);
  expect_numbers(scene["refit"],
                 {"field_only_ms", "geometry_ms", "bound_field_only_ms", "bound_geometry_ms",
                  "rebuild_ms", "step_total_ms", "step_total_default_packet_ms",
                  "ref_step_total_ms", "quality_ratio_after_steps"});
  EXPECT_GT(scene["ref"]["triangles"].asUInt64(), 0u);
  // --steps 2: one new step, measured for tetray and for the reference.
  EXPECT_GT(scene["refit"]["step_total_ms"].asDouble(), 0.0);
  EXPECT_GT(scene["refit"]["step_total_default_packet_ms"].asDouble(), 0.0);
  EXPECT_GT(scene["refit"]["ref_step_total_ms"].asDouble(), 0.0);
}

// Whether the ray from `eye` along `direction` meets the box [-1, 1]^3 (the slab test).
bool meets_unit_box(Vec3d eye, Vec3d direction) {
  double near = 0, far = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const double t0 = (-1 - eye[axis]) / direction[axis], t1 = (1 - eye[axis]) / direction[axis];
    near = std::max(near, std::min(t0, t1));
    far = std::min(far, std::max(t0, t1));
  }
  return near <= far;
}

void expect_counts_of_the_scene(const Json::Value& root) {
  ASSERT_TRUE(root["scenes"].isArray() && root["scenes"].size() == 1u);
  const Json::Value& counts = root["scenes"][0]["counts"];

  // The benchmark traces its first step, t = 0: the mesh is the box [-1, 1]^3 (jitter moves
  // interior points only) and the twist is off.
  const tetray::GyroidTwist gyroid = tetray::make_gyroid_twist(kCells, 0.0);
  const tetray::test::RenderScene scene =
      tetray::test::load_scene(gyroid.mesh.points, gyroid.mesh.tets, gyroid.field);
  const tetray::render::Camera camera = tetray::test::benchmark_camera(kSide);
  const std::vector<tetray::test::ReferenceHit> reference =
      tetray::test::ReferenceIntersector(scene.volume, {0.0}).trace_image(camera);
  std::uint64_t reference_hits = 0, grazing = 0, through_box = 0;
  const tetray::test::ReferenceCamera rays(camera);
  for (int j = 0; j < kSide; ++j) {
    for (int i = 0; i < kSide; ++i) {
      const tetray::test::ReferenceHit& hit = reference[static_cast<std::size_t>(j) * kSide + i];
      reference_hits += hit.hit;
      grazing += hit.isopolygon_edge_distance < tetray::test::kGrazingDistance;
      through_box += meets_unit_box(camera.eye, rays.pixel_direction(i, j));
    }
  }
  std::printf("reference hits %llu (%llu grazing), rays through the box %llu\n",
              static_cast<unsigned long long>(reference_hits),
              static_cast<unsigned long long>(grazing),
              static_cast<unsigned long long>(through_box));
  EXPECT_LE(reference_hits, through_box);
  for (const char* packet : {"1", "8x8", "16x16", "32x32"}) {
    const std::uint64_t hits = counts[packet]["hits"].asUInt64();
    EXPECT_EQ(counts[packet]["rays"].asUInt64(), std::uint64_t{kSide} * kSide) << packet;
    EXPECT_LE(hits, reference_hits + grazing) << packet;
    EXPECT_GE(hits + grazing, reference_hits) << packet;
  }
  // docs/architecture.md §6: hit/miss agreement with Embree on the same rays >= 99.9%, median
  // relative depth difference < 1e-5.
  const Json::Value& ref = root["scenes"][0]["ref"];
  EXPECT_GE(ref["depth_agree_fraction"].asDouble(), 0.999);
  EXPECT_LT(ref["depth_median_rel_diff"].asDouble(), 1e-5);
}

// One run of the benchmark for both checks: it is the slow part.
TEST(BenchSmoke, JsonHasEveryKeyAndItsCountsAgreeWithTheScene) {
  const Json::Value root = run_tiny_bench();
  expect_every_key(root);
  expect_counts_of_the_scene(root);
}

}  // namespace
