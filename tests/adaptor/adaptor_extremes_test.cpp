// Values a solver can pass that are finite but do not fit the renderer's float vertex store (a
// point at 1e308, a field scaled by 1e300) and non-finite times: each is refused with a message
// naming the point and the value, skipped under skip_tets, or (a NaN time) skipped by the time
// trigger without stopping it. Before, the first blanked the image, the second changed it, and
// a NaN time stopped an every_time trigger for the rest of the run, all with status ok.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <limits>

#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

class Extremes : public ::testing::Test {
 protected:
  void create(const std::string& top_lines = "") {
    Status status;
    adaptor_ = Adaptor::create_from_yaml(
        MPI_COMM_WORLD, plane_config(dir_.path().string(), ", writer_queue_depth: 0", top_lines),
        status);
    ASSERT_TRUE(adaptor_) << status.message;
  }

  Status execute(const PlaneScene& s, std::int64_t step, double time) {
    return adaptor_->execute(step, time, s.view(), s.fields(), {}, &report_);
  }

  fs::path png(int step) const {
    return dir_.path() / "plane" / ("plane_00000" + std::to_string(step) + ".png");
  }

  // The hits column of the log's row for `row` (1: the first rendered step).
  std::uint64_t logged_hits(std::size_t row) {
    adaptor_->finalize();
    return std::stoull(cell(read_csv((dir_.path() / "tetray_log.csv").string()), row, "hits"));
  }

  ScratchDir dir_;
  PlaneScene scene_ = make_plane_scene(4);
  std::unique_ptr<Adaptor> adaptor_;
  ExecuteReport report_;
};

TEST_F(Extremes, APointBeyondFloatRangeIsRefusedNamingPointAndValue) {
  create();
  PlaneScene bad = scene_;
  bad.mesh.points[3 * 20 + 1] = 1e308;
  const Status status = execute(bad, 0, 0);
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_NE(status.message.find("coordinate 1e+308 at point 20"), std::string::npos)
      << status.message;
  EXPECT_NE(status.message.find("float range"), std::string::npos) << status.message;
  EXPECT_FALSE(fs::exists(png(0)));
  EXPECT_TRUE(execute(scene_, 1, 1).ok());
}

TEST_F(Extremes, ADisplacementThatCarriesAPointTooFarIsRefused) {
  create();
  std::vector<double> displacement(scene_.mesh.points.size(), 0.0);
  displacement[3 * 7 + 2] = -2e12;
  MeshView mesh = scene_.view();
  mesh.points.displacement = displacement.data();
  const Status status = adaptor_->execute(0, 0, mesh, scene_.fields());
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_NE(status.message.find("at point 7"), std::string::npos) << status.message;
}

// A field is the input of its scenes only: they are skipped (partial), naming the value.
TEST_F(Extremes, AFieldScaledBeyondFloatRangeSkipsItsScene) {
  create();
  PlaneScene scaled = scene_;
  for (double& v : scaled.f) v *= 1e300;
  const Status status = execute(scaled, 0, 0);
  EXPECT_EQ(status.code, StatusCode::partial);
  EXPECT_NE(status.message.find("field value"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("float range"), std::string::npos) << status.message;
}

TEST_F(Extremes, UnderSkipTetsAFarPointSkipsOnlyItsTets) {
  create("nonfinite: skip_tets\n");
  PlaneScene bad = scene_;
  bad.mesh.points[3 * 20 + 1] = 1e308;
  const Status status = execute(bad, 0, 0);
  ASSERT_TRUE(status.ok()) << status.message;
  EXPECT_GT(report_.tets_skipped, 0u);
  EXPECT_LT(report_.tets_skipped, 24u);  // the tets around one point of a 4^3 grid
  // Most of the square is still drawn (the image was blank before).
  EXPECT_GT(logged_hits(1), expected_plane_hits().sure / 2);
}

TEST_F(Extremes, ANonFiniteTimeSkipsATimeTriggerWithoutStoppingIt) {
  create("trigger: {every_time: 1}\n");
  const double nan = std::numeric_limits<double>::quiet_NaN();
  ASSERT_TRUE(execute(scene_, 0, nan).ok());
  EXPECT_FALSE(report_.rendered);
  EXPECT_FALSE(adaptor_->will_render(1, nan));
  ASSERT_TRUE(execute(scene_, 1, 0.0).ok());
  EXPECT_TRUE(report_.rendered);
  ASSERT_TRUE(execute(scene_, 2, std::numeric_limits<double>::infinity()).ok());
  EXPECT_FALSE(report_.rendered);
  ASSERT_TRUE(execute(scene_, 3, 1.0).ok());
  EXPECT_TRUE(report_.rendered);
  EXPECT_TRUE(fs::exists(png(1)));
  EXPECT_TRUE(fs::exists(png(3)));
  EXPECT_FALSE(fs::exists(png(0)) || fs::exists(png(2)));
}

}  // namespace
}  // namespace tetray::testing
