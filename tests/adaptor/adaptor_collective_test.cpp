// Collective status, run under mpirun on 2 and 3 ranks (and a ctest timeout, so a hang fails):
// whatever goes wrong on one rank (the writer rank's disk, one rank's data, one rank's missing
// field) every rank returns the same status from the same call, naming the rank; a field fault
// skips only the scenes that read the field; off-trigger steps need no other rank.
#include <gtest/gtest.h>
#include <signal.h>
#include <sys/resource.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>

#include "plane_scene.hpp"
#include "same_status.hpp"
#include "shared_dir.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

int last_rank() { return world_size() - 1; }

// A full disk without privileges: every write of this process into a file past `bytes` fails
// with EFBIG (SIGXFSZ ignored, so the write returns the error instead of ending the process).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_ = signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    EXPECT_EQ(setrlimit(RLIMIT_FSIZE, &limit), 0) << std::strerror(errno);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    signal(SIGXFSZ, previous_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  sighandler_t previous_ = SIG_DFL;
};

std::unique_ptr<Adaptor> make(const std::string& dir, const std::string& output_keys,
                              const std::string& top_lines = "",
                              const std::string& scene_lines = "") {
  Status status;
  auto a = Adaptor::create_from_yaml(
      MPI_COMM_WORLD, plane_config(dir, ", formats: [png]" + output_keys, top_lines) + scene_lines,
      status);
  EXPECT_TRUE(a) << status.message;
  return a;
}

std::string writer_on_last_rank() { return ", writer_rank: " + std::to_string(last_rank()); }

Status execute(Adaptor& a, const PlaneScene& scene, std::int64_t step,
               std::vector<FieldView> fields, const Changes& changes = {},
               ExecuteReport* report = nullptr) {
  return a.execute(step, static_cast<double>(step), scene.view(), fields, changes, report);
}

bool starts_with(const std::string& text, const std::string& prefix) {
  return text.rfind(prefix, 0) == 0;
}

fs::path image(const std::string& dir, const std::string& scene, int step) {
  char name[64];
  std::snprintf(name, sizeof name, "%s_%06d.png", scene.c_str(), step);
  return fs::path(dir) / scene / name;
}

// Writes inline (queue depth 0), so step 2's write fails inside step 2's call, after its last
// agreement: step 3 (off-trigger) still returns ok everywhere, step 4 reports it everywhere.
TEST(AdaptorCollective, WriterErrorMidRunIsEveryRanksStatusAtTheNextRenderStep) {
  const SharedDir shared("writer_error");
  const PlaneScene scene = make_plane_scene(4);
  auto a = make(shared.path(), writer_on_last_rank() + ", writer_queue_depth: 0",
                "trigger: {every: 2}\n");
  ASSERT_TRUE(a);
  const auto fields = scene.fields();
  ASSERT_TRUE(execute(*a, scene, 0, fields).ok());
  {
    std::optional<FileSizeLimit> full_disk;
    if (rank() == last_rank()) full_disk.emplace(1);
    for (int step = 1; step <= 3; ++step) {
      const Status status = execute(*a, scene, step, fields);
      EXPECT_TRUE(status.ok()) << "step " << step << ": " << status.message;
    }
    const Status status = execute(*a, scene, 4, fields);
    expect_same_on_every_rank(status);
    EXPECT_EQ(status.code, StatusCode::io_error);
    EXPECT_TRUE(starts_with(status.message, rank_prefix(last_rank()))) << status.message;
    EXPECT_NE(status.message.find("plane_000002"), std::string::npos) << status.message;
    EXPECT_NE(status.message.find(std::strerror(EFBIG)), std::string::npos) << status.message;
  }
  // The disk has room again: the run goes on.
  const Status recovered = execute(*a, scene, 6, fields);
  EXPECT_TRUE(recovered.ok()) << recovered.message;
  EXPECT_TRUE(a->finalize().ok());
  if (rank() != last_rank()) return;
  EXPECT_TRUE(fs::exists(image(shared.path(), "plane", 0)));
  EXPECT_FALSE(fs::exists(image(shared.path(), "plane", 2)));
  EXPECT_FALSE(fs::exists(image(shared.path(), "plane", 4)));  // the failed call rendered nothing
  EXPECT_TRUE(fs::exists(image(shared.path(), "plane", 6)));
}

// The writer thread fails on the last step's image; only finalize can tell, on every rank.
TEST(AdaptorCollective, WriterErrorAtFinalizeIsEveryRanksStatus) {
  const SharedDir shared("finalize_error");
  const PlaneScene scene = make_plane_scene(4);
  auto a = make(shared.path(), writer_on_last_rank() + ", writer_queue_depth: 2");
  ASSERT_TRUE(a);
  std::optional<FileSizeLimit> full_disk;
  if (rank() == last_rank()) full_disk.emplace(1);
  const Status status = execute(*a, scene, 0, scene.fields());
  EXPECT_TRUE(status.ok()) << status.message;
  const Status finalized = a->finalize();
  full_disk.reset();
  expect_same_on_every_rank(finalized);
  EXPECT_EQ(finalized.code, StatusCode::io_error);
  EXPECT_TRUE(starts_with(finalized.message, rank_prefix(last_rank()))) << finalized.message;
  EXPECT_NE(finalized.message.find("plane_000000"), std::string::npos) << finalized.message;
  EXPECT_TRUE(a->finalize().ok()) << "finalize is idempotent";
}

TEST(AdaptorCollective, UnwritableOutputDirectoryFailsCreateOnEveryRank) {
  const SharedDir shared("unwritable");
  const fs::path file = fs::path(shared.path()) / "regular_file";
  if (rank() == 0) std::ofstream(file) << "not a directory";
  MPI_Barrier(MPI_COMM_WORLD);
  Status status;
  const auto a = Adaptor::create_from_yaml(
      MPI_COMM_WORLD, plane_config((file / "out").string(), writer_on_last_rank()), status);
  EXPECT_FALSE(a);
  expect_same_on_every_rank(status);
  EXPECT_EQ(status.code, StatusCode::io_error);
  EXPECT_TRUE(starts_with(status.message, rank_prefix(last_rank()))) << status.message;
  EXPECT_NE(status.message.find((file / "out").string()), std::string::npos) << status.message;
}

TEST(AdaptorCollective, BadDataOnOneRankIsEveryRanksError) {
  const SharedDir shared("bad_points");
  PlaneScene scene = make_plane_scene(4);
  auto a = make(shared.path(), "");
  ASSERT_TRUE(a);
  const double good = scene.mesh.points[7];
  if (rank() == last_rank()) scene.mesh.points[7] = std::numeric_limits<double>::quiet_NaN();
  Status status = execute(*a, scene, 0, scene.fields());
  expect_same_on_every_rank(status);
  EXPECT_EQ(status.code, StatusCode::invalid_argument);
  EXPECT_TRUE(starts_with(status.message, rank_prefix(last_rank()))) << status.message;
  EXPECT_NE(status.message.find("non-finite coordinate"), std::string::npos) << status.message;
  scene.mesh.points[7] = good;
  status = execute(*a, scene, 1, scene.fields());
  EXPECT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(a->finalize().ok());
  if (rank() != 0) return;
  EXPECT_FALSE(fs::exists(image(shared.path(), "plane", 0)));
  EXPECT_TRUE(fs::exists(image(shared.path(), "plane", 1)));
}

// Two scenes on f, the second colored by g; the last rank's g is missing, then NaN (policy
// error), then still NaN with the caller saying nothing changed, then good. Then f is NaN there:
// both scenes are skipped.
TEST(AdaptorCollective, AFieldFaultOnOneRankSkipsOnlyItsScenesOnEveryRank) {
  const SharedDir shared("skip_scene");
  const PlaneScene scene = make_plane_scene(4);
  auto a = make(shared.path(), "", "",
                "  - {name: by_g, field: f, isovalues: [0.25], color_by: g, "
                "image: {width: 32, height: 32}}\n");
  ASSERT_TRUE(a);
  const bool faulty = rank() == last_rank();
  const std::string by_rank = rank_prefix(last_rank());
  PlaneScene nan_g = scene;
  nan_g.g[5] = std::numeric_limits<double>::quiet_NaN();
  PlaneScene nan_f = scene;
  nan_f.f[5] = std::numeric_limits<double>::quiet_NaN();
  const std::vector<FieldView> only_f = {FieldView::of("f", std::span<const double>(scene.f))};
  struct Step {
    const PlaneScene& data;
    std::vector<FieldView> fields;
    Changes changes;
    std::vector<std::string> skipped;
    std::string message;  // of the skip, after "rank N: "
  };
  const Changes nothing{false, false, false};
  const std::vector<Step> steps = {
      {scene,
       faulty ? only_f : scene.fields(),
       {},
       {"by_g"},
       "scene 'by_g' skipped: " + by_rank + "field 'g' used by scene 'by_g' was not passed"},
      {faulty ? nan_g : scene,
       (faulty ? nan_g : scene).fields(),
       {},
       {"by_g"},
       "scene 'by_g' skipped: " + by_rank + "mesh with field 'g': non-finite field value"},
      {faulty ? nan_g : scene,
       (faulty ? nan_g : scene).fields(),
       nothing,
       {"by_g"},
       "scene 'by_g' skipped: " + by_rank + "mesh with field 'g': non-finite field value"},
      {scene, scene.fields(), {}, {}, ""},
      {faulty ? nan_f : scene,
       (faulty ? nan_f : scene).fields(),
       {},
       {"plane", "by_g"},
       "scene 'plane' skipped: " + by_rank + "mesh with field 'f': non-finite field value"},
  };
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const Step& s = steps[k];
    const auto step = static_cast<std::int64_t>(k);
    ExecuteReport report;
    const Status status = execute(*a, s.data, step, s.fields, s.changes, &report);
    expect_same_on_every_rank(status);
    EXPECT_EQ(status.code, s.skipped.empty() ? StatusCode::ok : StatusCode::partial) << k;
    EXPECT_TRUE(starts_with(status.message, s.message)) << k << ": " << status.message;
    EXPECT_EQ(report.skipped_scenes, s.skipped) << k;
    EXPECT_EQ(report.scenes_rendered, static_cast<int>(2 - s.skipped.size())) << k;
    EXPECT_EQ(report.rendered, s.skipped.size() < 2) << k;
  }
  EXPECT_TRUE(a->finalize().ok());
  if (rank() != 0) return;
  for (int step = 0; step < 5; ++step) {
    EXPECT_EQ(fs::exists(image(shared.path(), "plane", step)), step != 4) << step;
    EXPECT_EQ(fs::exists(image(shared.path(), "by_g", step)), step == 3) << step;
  }
}

// The last rank has points but no tets and passes no field: nothing to render there, nothing
// missing.
TEST(AdaptorCollective, ARankWithoutTetsNeedsNoFields) {
  const SharedDir shared("no_tets");
  const PlaneScene scene = make_plane_scene(4);
  auto a = make(shared.path(), "");
  ASSERT_TRUE(a);
  MeshView view = scene.view();
  std::vector<FieldView> fields = scene.fields();
  if (rank() == last_rank()) {
    view.tets.count = 0;
    fields.clear();
  }
  ExecuteReport report;
  const Status status = a->execute(0, 0, view, fields, {}, &report);
  expect_same_on_every_rank(status);
  EXPECT_TRUE(status.ok()) << status.message;
  EXPECT_EQ(report.scenes_rendered, 1);
  EXPECT_TRUE(a->finalize().ok());
  if (rank() != 0) return;
  const auto log = read_csv(shared.path() + "/tetray_log.csv");
  ASSERT_EQ(log.size(), 2u);
  const ExpectedHits expected = expected_plane_hits();
  const auto hits = std::stoull(cell(log, 1, "hits"));
  EXPECT_GE(hits, expected.sure);
  EXPECT_LE(hits, expected.sure + expected.edge);
}

// The last rank cannot prepare its views (as when the VTK bridge's conversion fails): on a
// render step every rank fails with its message; on an off-trigger step every rank returns ok
// and the next render step reports it.
TEST(AdaptorCollective, ARankThatCannotPrepareItsViewsFailsTheStepOnEveryRank) {
  const SharedDir shared("execute_failed");
  const PlaneScene scene = make_plane_scene(4);
  auto a = make(shared.path(), "", "trigger: {every: 2}\n");
  ASSERT_TRUE(a);
  const auto fields = scene.fields();
  const Status cannot{StatusCode::invalid_argument, "cannot convert the grid"};
  const auto step = [&](std::int64_t k) {
    return rank() == last_rank() ? a->execute_failed(k, static_cast<double>(k), cannot)
                                 : execute(*a, scene, k, fields);
  };
  for (const std::int64_t failing : {0, 1}) {
    Status status = step(failing);
    if (failing == 1) {
      EXPECT_TRUE(status.ok()) << "off-trigger: " << status.message;
      status = execute(*a, scene, 2, fields);
    }
    expect_same_on_every_rank(status);
    EXPECT_EQ(status.code, StatusCode::invalid_argument) << failing;
    EXPECT_EQ(status.message, rank_prefix(last_rank()) + cannot.message) << failing;
  }
  const Status recovered = execute(*a, scene, 4, fields);
  EXPECT_TRUE(recovered.ok()) << recovered.message;
  EXPECT_TRUE(a->finalize().ok());
  if (rank() != 0) return;
  for (int k : {0, 2}) EXPECT_FALSE(fs::exists(image(shared.path(), "plane", k))) << k;
  EXPECT_TRUE(fs::exists(image(shared.path(), "plane", 4)));
}

// Rank 0 alone makes nine off-trigger calls: were any of them collective, the ranks would
// mismatch their collectives at step 10 and hang (the ctest timeout fails the test).
TEST(AdaptorCollective, OffTriggerStepsNeedNoOtherRank) {
  const SharedDir shared("off_trigger");
  const PlaneScene scene = make_plane_scene(4);
  auto a = make(shared.path(), "", "trigger: {every: 10}\n");
  ASSERT_TRUE(a);
  const auto fields = scene.fields();
  ASSERT_TRUE(execute(*a, scene, 0, fields).ok());
  if (rank() == 0) {
    for (int step = 1; step < 10; ++step) EXPECT_TRUE(execute(*a, scene, step, fields).ok());
  }
  const Status status = execute(*a, scene, 10, fields);
  EXPECT_TRUE(status.ok()) << status.message;
  EXPECT_TRUE(a->finalize().ok());
  if (rank() == 0) {
    EXPECT_TRUE(fs::exists(image(shared.path(), "plane", 10)));
  }
}

}  // namespace
}  // namespace tetray::testing
