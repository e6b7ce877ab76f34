// A small tetray-split-study run: its JSON has a row per field, size and level, and the error
// behaves as interpolation theory says. Sampling each cell on a finer lattice (level 2) must shrink
// the mean depth error against the reference, and so must doubling the cells of the mesh; a row
// that showed no error at all would mean the reference is the image itself.
#include <gtest/gtest.h>
#include <json/json.h>

#include <string>

#include "support/json_output.hpp"

namespace {

Json::Value run_study() {
  return tetray::testing::run_for_json(
      std::string(TETRAY_SPLIT_STUDY) +
          " --sizes 4 8 --levels 1 2 --reference 48 --size 128 --split-sizes 6 --split-runs 1",
      "tetray_split_study.json");
}

// The row of `field`, `cells` and `level`.
const Json::Value& row(const Json::Value& rows, const std::string& field, int cells, int level) {
  for (const Json::Value& r : rows) {
    if (r["field"].asString() == field && r["cells_per_side"].asInt() == cells &&
        r["level"].asInt() == level) {
      return r;
    }
  }
  static const Json::Value missing;
  ADD_FAILURE() << "no row " << field << " " << cells << " " << level;
  return missing;
}

TEST(SplitStudy, ErrorFallsWithLevelAndMeshSize) {
  const Json::Value rows = run_study()["images"];
  ASSERT_TRUE(rows.isArray());
  EXPECT_EQ(rows.size(), 8u);
  for (const char* field : {"Q1 hexahedra", "Q2 hexahedra"}) {
    const auto error = [&](int cells, int level) {
      return row(rows, field, cells, level)["mean_depth_error"].asDouble();
    };
    EXPECT_GT(error(4, 1), 0) << field;
    EXPECT_LT(error(4, 2), 0.6 * error(4, 1)) << field;
    EXPECT_LT(error(8, 1), 0.6 * error(4, 1)) << field;
    EXPECT_GT(row(rows, field, 4, 2)["tets"].asUInt64(),
              7 * row(rows, field, 4, 1)["tets"].asUInt64());
    EXPECT_TRUE(row(rows, field, 8, 2)["trace_ms"].isNumeric()) << field;
  }
}

// The split's timing rows: on 6^3 hexahedra nothing hangs; with the half x >= 0 refined, the
// interface holds 6 x 6 coarse faces, each with a hanging centre, and 2 x 7 x 6 coarse edges, each
// with a hanging midpoint; every coarse cell splits into 6 tets at least, every fine one into 6.
TEST(SplitStudy, TimesTheSplitWithTheHangingNodesItFinds) {
  const Json::Value rows = run_study()["split"];
  ASSERT_TRUE(rows.isArray());
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0]["hanging_midpoints"].asUInt64(), 0u);
  EXPECT_EQ(rows[0]["tets"].asUInt64(), 6u * 216);
  EXPECT_EQ(rows[1]["cells"].asUInt64(), 108u + 8 * 108);
  EXPECT_EQ(rows[1]["hanging_centres"].asUInt64(), 36u);
  EXPECT_EQ(rows[1]["hanging_midpoints"].asUInt64(), 84u);
  EXPECT_GT(rows[1]["tets"].asUInt64(), 6u * (108 + 8 * 108));
  EXPECT_TRUE(rows[1]["split_ms"].isNumeric());
  EXPECT_TRUE(rows[1]["split_without_search_ms"].isNumeric());
}

}  // namespace
