// Bad input, bad configs and failing disks: each gives a clear status, the next execute still
// works, and nothing already written is damaged.
#include <gtest/gtest.h>
#include <sys/mount.h>

#include <filesystem>
#include <fstream>
#include <limits>

#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

// One adaptor writing inline (queue depth 0), so a write error is met within the call that
// renders the image (after its last agreement: the next render step reports it).
class Reliability : public ::testing::Test {
 protected:
  void SetUp() override {
    Status status;
    adaptor_ = Adaptor::create_from_yaml(MPI_COMM_WORLD, config(), status);
    ASSERT_TRUE(adaptor_) << status.message;
    ASSERT_TRUE(execute(scene_, 0).ok());
    first_png_ = slurp(png(0));
    ASSERT_FALSE(first_png_.empty());
  }

  virtual std::string config() {
    return plane_config(dir_.path().string(), ", writer_queue_depth: 0");
  }

  Status execute(const PlaneScene& s, std::int64_t step, std::vector<FieldView> fields = {}) {
    if (fields.empty()) fields = s.fields();
    return adaptor_->execute(step, static_cast<double>(step), s.view(), fields, {}, &report_);
  }

  fs::path png(int step) const {
    return dir_.path() / "plane" / ("plane_00000" + std::to_string(step) + ".png");
  }

  // The solver goes on: a good step renders and step 0's image is untouched.
  void expect_recovery(std::int64_t step) {
    const Status status = execute(scene_, step);
    EXPECT_TRUE(status.ok()) << status.message;
    EXPECT_TRUE(fs::exists(png(static_cast<int>(step))));
    EXPECT_EQ(slurp(png(0)), first_png_);
  }

  ScratchDir dir_;
  PlaneScene scene_ = make_plane_scene(4);
  std::unique_ptr<Adaptor> adaptor_;
  ExecuteReport report_;
  std::string first_png_;
};

TEST_F(Reliability, IndexOutOfRange) {
  PlaneScene bad = scene_;
  bad.mesh.tets[4 * 7 + 2] = static_cast<std::int64_t>(bad.mesh.point_count()) + 5;
  const Status status = execute(bad, 1);
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_NE(status.message.find("tet 7"), std::string::npos) << status.message;
  EXPECT_FALSE(fs::exists(png(1)));
  expect_recovery(2);
}

// Indices are checked again when the point count changes even if the caller says the topology
// did not: here the last point is gone and a tet still names it.
TEST_F(Reliability, IndicesCheckedAgainWhenThePointCountChanges) {
  const Changes moved{true, false, true};
  const auto fields = scene_.fields();
  ASSERT_TRUE(adaptor_->execute(1, 1.0, scene_.view(), fields, moved).ok());
  PlaneScene fewer = scene_;
  const std::size_t last = fewer.mesh.point_count() - 1;
  fewer.mesh.points.resize(3 * last);
  fewer.f.resize(last);
  fewer.g.resize(last);
  const auto fewer_fields = fewer.fields();
  const Status status = adaptor_->execute(2, 2.0, fewer.view(), fewer_fields, moved);
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_NE(status.message.find("point index " + std::to_string(last) + " outside [0, " +
                                std::to_string(last) + ")"),
            std::string::npos)
      << status.message;
  EXPECT_FALSE(fs::exists(png(2)));
  expect_recovery(3);
}

TEST_F(Reliability, NonFiniteValueUnderErrorPolicy) {
  PlaneScene bad = scene_;
  bad.f[10] = std::numeric_limits<double>::quiet_NaN();
  bad.mesh.points[3 * 20 + 1] = std::numeric_limits<double>::infinity();
  const Status status = execute(bad, 1);
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_NE(status.message.find("non-finite"), std::string::npos) << status.message;
  expect_recovery(2);
}

// The only scene is skipped: the call completes (partial), renders nothing, and says why.
TEST_F(Reliability, MissingFieldSkipsItsScene) {
  const std::vector<FieldView> only_g = {FieldView::of("g", std::span<const double>(scene_.g))};
  const Status status = execute(scene_, 1, only_g);
  EXPECT_EQ(status.code, StatusCode::partial);
  EXPECT_FALSE(status.failed());
  EXPECT_EQ(status.message.rfind("scene 'plane' skipped: field 'f'", 0), 0u) << status.message;
  EXPECT_NE(status.message.find("passed: g"), std::string::npos) << status.message;
  EXPECT_EQ(report_.skipped_scenes, std::vector<std::string>{"plane"});
  EXPECT_FALSE(report_.rendered);
  EXPECT_FALSE(fs::exists(png(1)));
  expect_recovery(2);
  EXPECT_TRUE(report_.skipped_scenes.empty());
}

TEST_F(Reliability, MismatchedArraySizes) {
  const std::vector<FieldView> short_f = {
      FieldView::of("f", std::span<const double>(scene_.f).first(scene_.f.size() - 1))};
  const Status status = execute(scene_, 1, short_f);
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_NE(status.message.find(std::to_string(scene_.f.size() - 1) + " values but the mesh has " +
                                std::to_string(scene_.f.size()) + " points"),
            std::string::npos)
      << status.message;
  MeshView null_points = scene_.view();
  null_points.points.xyz = nullptr;
  const auto fields = scene_.fields();
  const Status null_status = adaptor_->execute(1, 1, null_points, fields);
  EXPECT_EQ(null_status.code, StatusCode::invalid_argument);
  EXPECT_NE(null_status.message.find("points.xyz is null"), std::string::npos);
  expect_recovery(2);
}

TEST_F(Reliability, FullDisk) {
  // A tiny tmpfs that the images then fill; skipped where mounting is not allowed.
  const fs::path mount_point = dir_.path() / "tiny";
  fs::create_directories(mount_point);
  if (::mount("tmpfs", mount_point.c_str(), "tmpfs", 0, "size=256k") != 0) {
    GTEST_SKIP() << "cannot mount a tmpfs here";
  }
  struct Unmount {
    std::string path;
    ~Unmount() { ::umount(path.c_str()); }
  } unmount{mount_point.string()};
  Status status;
  auto a = Adaptor::create_from_yaml(
      MPI_COMM_WORLD, plane_config(mount_point.string(), ", writer_queue_depth: 0"), status);
  ASSERT_TRUE(a) << status.message;
  const auto fields = scene_.fields();
  ASSERT_TRUE(a->execute(0, 0, scene_.view(), fields).ok());
  const fs::path first = mount_point / "plane" / "plane_000000.png";
  const std::string first_bytes = slurp(first);
  const std::string log_before = slurp(mount_point / "tetray_log.csv");
  {
    std::ofstream filler(mount_point / "filler", std::ios::binary);
    const std::string block(4096, 'x');
    while (filler.write(block.data(), static_cast<std::streamsize>(block.size()))) {
    }
  }
  // The write fails after the step's last agreement: the next render step reports it.
  status = a->execute(1, 1, scene_.view(), fields);
  EXPECT_TRUE(status.ok()) << status.message;
  EXPECT_EQ(slurp(first), first_bytes);
  EXPECT_EQ(slurp(mount_point / "tetray_log.csv"), log_before);
  fs::remove(mount_point / "filler");
  status = a->execute(2, 2, scene_.view(), fields);
  EXPECT_EQ(status.code, StatusCode::io_error);
  EXPECT_NE(status.message.find(mount_point.string()), std::string::npos) << status.message;
  EXPECT_FALSE(fs::exists(mount_point / "plane" / "plane_000002.png"));
  status = a->execute(3, 3, scene_.view(), fields);
  EXPECT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(fs::exists(mount_point / "plane" / "plane_000003.png"));
  EXPECT_TRUE(a->finalize().ok());
}

TEST_F(Reliability, WriterThreadErrorReachesFinalize) {
  Status status;
  const fs::path out = dir_.path() / "async";
  auto a = Adaptor::create_from_yaml(MPI_COMM_WORLD, plane_config(out.string()), status);
  ASSERT_TRUE(a) << status.message;
  // The scene's image directory becomes a regular file: every image write fails.
  fs::remove_all(out / "plane");
  std::ofstream(out / "plane") << "not a directory";
  const auto fields = scene_.fields();
  status = a->execute(0, 0, scene_.view(), fields);
  EXPECT_TRUE(status.ok()) << status.message;
  const Status finalized = a->finalize();
  EXPECT_EQ(finalized.code, StatusCode::io_error);
  EXPECT_NE(finalized.message.find("plane_000000"), std::string::npos) << finalized.message;
}

TEST_F(Reliability, PerRankImageErrorIsTheStepsStatus) {
  Status status;
  const fs::path out = dir_.path() / "per_rank";
  auto a = Adaptor::create_from_yaml(MPI_COMM_WORLD,
                                     plane_config(out.string(), ", per_rank_images: true"), status);
  ASSERT_TRUE(a) << status.message;
  // The per-rank image directory becomes a regular file: the rank's image write fails.
  fs::remove_all(out / "plane" / "ranks");
  std::ofstream(out / "plane" / "ranks") << "not a directory";
  status = a->execute(0, 0, scene_.view(), scene_.fields());
  EXPECT_EQ(status.code, StatusCode::io_error);
  EXPECT_NE(status.message.find("plane_000000_rank0000.png"), std::string::npos) << status.message;
  EXPECT_TRUE(a->finalize().ok());
}

TEST_F(Reliability, UnwritableOutputDirectory) {
  const fs::path file = dir_.path() / "regular_file";
  std::ofstream(file) << "x";
  Status status;
  auto a = Adaptor::create_from_yaml(MPI_COMM_WORLD, plane_config((file / "out").string()), status);
  EXPECT_FALSE(a);
  EXPECT_EQ(status.code, StatusCode::io_error);
  EXPECT_NE(status.message.find((file / "out").string()), std::string::npos) << status.message;
  expect_recovery(1);
}

TEST_F(Reliability, ConfigErrorsNameFileLineAndKey) {
  Status status;
  auto a = Adaptor::create_from_yaml(
      MPI_COMM_WORLD, plane_config(dir_.path().string(), "", "", "    isovalue: [1]\n"), status);
  EXPECT_FALSE(a);
  EXPECT_EQ(status.code, StatusCode::config_error);
  EXPECT_NE(status.message.find("<yaml string>:8:"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("scenes[0].isovalue"), std::string::npos) << status.message;
  const fs::path file = dir_.path() / "bad.yaml";
  std::ofstream(file) << plane_config(dir_.path().string(), "", "", "    trigger: {every: -1}\n");
  a = Adaptor::create(MPI_COMM_WORLD, file.string(), status);
  EXPECT_FALSE(a);
  EXPECT_EQ(status.code, StatusCode::config_error);
  EXPECT_NE(status.message.find(file.string() + ":8:"), std::string::npos) << status.message;
  EXPECT_NE(status.message.find("scenes[0].trigger.every"), std::string::npos) << status.message;
  expect_recovery(1);
}

TEST_F(Reliability, ExecuteAfterFinalizeIsAnError) {
  ASSERT_TRUE(adaptor_->finalize().ok());
  EXPECT_TRUE(adaptor_->finalize().ok());
  EXPECT_EQ(execute(scene_, 1).code, StatusCode::not_initialized);
}

class SkipTets : public Reliability {
  std::string config() override {
    return plane_config(dir_.path().string(), ", writer_queue_depth: 0", "nonfinite: skip_tets\n");
  }
};

TEST_F(SkipTets, SkipsAndCountsTetsTouchingNonFiniteValues) {
  PlaneScene bad = scene_;
  const std::int64_t nan_point = bad.mesh.point_index(2, 2, 1);
  bad.f[static_cast<std::size_t>(nan_point)] = std::numeric_limits<double>::quiet_NaN();
  std::uint64_t touching = 0;
  for (std::size_t t = 0; t < bad.mesh.tet_count(); ++t) {
    touching += std::count(&bad.mesh.tets[4 * t], &bad.mesh.tets[4 * t + 4], nan_point) > 0;
  }
  ASSERT_GT(touching, 0u);
  const Status status = execute(bad, 1);
  EXPECT_TRUE(status.ok()) << status.message;
  EXPECT_EQ(report_.tets_skipped, touching);
  EXPECT_TRUE(fs::exists(png(1)));
  ASSERT_TRUE(adaptor_->finalize().ok());
  const auto log = read_csv(dir_ / "tetray_log.csv");
  ASSERT_EQ(log.size(), 3u);
  EXPECT_EQ(cell(log, 2, "skipped_tets"), std::to_string(touching));
  EXPECT_EQ(cell(log, 2, "kept_tets"), std::to_string(bad.mesh.tet_count() - touching));
}

}  // namespace
}  // namespace tetray::testing
