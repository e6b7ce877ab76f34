// tetray-composite-bench's transparent rows (tools/composite_bench/fragment_rows.hpp) on 2 ranks
// of a 64 x 64 image: one row per coverage, each rank's fragment count two per covered pixel (the
// dense image covers every pixel on every rank), the ratio the two times' quotient and the
// target's verdict the ratio against 2.
#include <gtest/gtest.h>
#include <json/json.h>

#include <string>

#include "support/json_output.hpp"

namespace {

TEST(CompositeBenchFragments, ComparesTwoLayersPerHitWithTheOpaqueImage) {
  const Json::Value root = tetray::testing::run_for_json(
      // Open MPI's own allocations are no leak of tetray's (a sanitized build checks leaks).
      std::string("ASAN_OPTIONS=detect_leaks=0 ") + TETRAY_MPIEXEC + " -np 2 " +
          TETRAY_MPIEXEC_FLAGS + " " + TETRAY_COMPOSITE_BENCH_EXE +
          " --sizes 64 --ranks 2 --algorithms automatic --repeat 1",
      "tetray_composite_bench_fragments.json");
  const Json::Value& rows = root["fragments"];
  ASSERT_TRUE(rows.isArray());
  ASSERT_EQ(rows.size(), 2u);
  for (const Json::Value& row : rows) {
    const std::string mode = row["mode"].asString();
    EXPECT_EQ(row["ranks"].asInt(), 2) << mode;
    EXPECT_GT(row["opaque_ms"].asDouble(), 0) << mode;
    EXPECT_GT(row["fragments_ms"].asDouble(), 0) << mode;
    const double ratio = row["fragments_ms"].asDouble() / row["opaque_ms"].asDouble();
    EXPECT_NEAR(row["ratio"].asDouble(), ratio, 1e-3 * ratio) << mode;
    EXPECT_EQ(row["target_ratio"].asDouble(), 2.0) << mode;
    EXPECT_EQ(row["target_met"].asBool(), row["ratio"].asDouble() <= 2.0) << mode;
    const double fragments = row["fragments_per_rank"].asDouble();
    if (mode == "dense") {
      EXPECT_EQ(fragments, 2.0 * 64 * 64);
    } else {
      EXPECT_GT(fragments, 0) << mode;
      EXPECT_LE(fragments, 2.0 * 64 * 64) << mode;
    }
  }
}

}  // namespace
