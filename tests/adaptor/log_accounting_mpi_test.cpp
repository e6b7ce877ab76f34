// The timing log accounts for the whole wait: for every rendered step, the stage columns of
// tetray_log.csv (every `_ms` column but the writer thread's encode_ms and write_ms and the total
// blocked_ms), summed over the step's rows, equal the time the solver was blocked in that
// execute call as ExecuteReport::seconds_blocked gives it. Four scenes turn every modality on
// (opaque isosurfaces colored by a field with annotations and two orbit views, transparent
// layers, smooth shading with a shadowing light and a capped clip, a volume with surfaces) plus
// probes, over steps that build, refit the field, move the points and change nothing, on the
// gyroid split into slabs over the ranks.
#include <gtest/gtest.h>
#include <mpi.h>

#include <chrono>
#include <cmath>
#include <map>
#include <string>
#include <vector>

#include "plane_scene.hpp"
#include "shared_dir.hpp"
#include "slab_partition.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::testing {
namespace {

const GyroidWithTemperature& scene() {
  static const GyroidWithTemperature s = gyroid_with_temperature({0, 0.6, -0.3, 0.2});
  return s;
}

constexpr const char* kCamera =
    "    camera: {eye: [2.5, 1.8, 3.2], look_at: [0, 0, 0], up: [0, 1, 0], fov_deg: 40}\n"
    "    image: {width: 96, height: 72}\n";

std::string config(const std::string& directory) {
  return "output: {directory: " + directory +
         ", formats: [exr, png], cinema: true, quiet: true}\n"
         "scenes:\n"
         "  - name: opaque\n"
         "    field: f\n"
         "    isovalues: [0, 0.5]\n"
         "    color_by: temperature\n"
         "    annotations: {colorbar: true, time: true, title: accounts}\n"
         "    orbit: {azimuth: [0, 90]}\n" +
         kCamera +
         "  - name: transparent\n"
         "    field: f\n"
         "    isovalues: [0]\n"
         "    opacity: [0.5]\n"
         "    max_layers: 4\n" +
         kCamera +
         "  - name: cut\n"
         "    field: temperature\n"
         "    isovalues: [0.1]\n"
         "    shading: smooth\n"
         "    lights: [{type: headlight}, {type: point, position: [2, 3, 1.5], shadows: true}]\n"
         "    clip:\n"
         "      planes: [{point: [0, 0, 0.2], normal: [0, 0, 1]}]\n"
         "      cap: {field: f, colormap: coolwarm, range: auto}\n" +
         kCamera +
         "  - name: heat\n"
         "    field: temperature\n"
         "    volume: {colormap: coolwarm, range: auto, opacity: [[-0.5, 0], [0, 3], [0.5, 0]],\n"
         "             unit_distance: 0.5}\n"
         "    surfaces: {field: f, isovalues: [0], opacity: [0.3]}\n" +
         kCamera +
         "probes:\n"
         "  - name: axis\n"
         "    fields: [f, temperature]\n"
         "    lines: [{from: [-1, 0.1, 0.1], to: [1, 0.1, 0.1], samples: 9}]\n";
}

// What the solver changes before each step: everything, the temperature, the points, nothing.
const Changes kSteps[] = {{true, true, true}, {false, false, true}, {true, false, true}, {}};
constexpr int kStepCount = 4;

// This rank's blocked time per step, from the report, and as the test's own clock saw the call.
struct Blocked {
  std::vector<double> reported_ms, around_call_ms;
};

Blocked run(const std::string& directory) {
  Blocked blocked;
  Status status;
  auto adaptor = Adaptor::create_from_yaml(MPI_COMM_WORLD, config(directory), status);
  EXPECT_TRUE(adaptor) << status.message;
  if (!adaptor) return blocked;
  const Slab part = x_slab(scene().gyroid.mesh, rank(), world_size());
  std::vector<double> points = scene().gyroid.mesh.points, temperature = scene().temperature;
  TetsView tets = TetsView::of(std::span<const std::int64_t>(part.tets));
  tets.global_ids = part.ids.data();
  for (int step = 0; step < kStepCount; ++step) {
    if (step == 1)
      for (double& t : temperature) t += 0.05;
    if (step == 2)
      for (double& p : points) p *= 1.02;
    const MeshView mesh{PointsView::of(std::span<const double>(points)), tets};
    const FieldView fields[] = {FieldView::of("f", std::span<const double>(scene().gyroid.field)),
                                FieldView::of("temperature", std::span<const double>(temperature))};
    ExecuteReport report;
    const auto before = std::chrono::steady_clock::now();
    status = adaptor->execute(step, 0.1 * step, mesh, fields, kSteps[step], &report);
    const std::chrono::duration<double, std::milli> call =
        std::chrono::steady_clock::now() - before;
    EXPECT_TRUE(status.ok()) << status.message;
    EXPECT_TRUE(report.rendered);
    blocked.reported_ms.push_back(report.seconds_blocked * 1e3);
    blocked.around_call_ms.push_back(call.count());
  }
  EXPECT_TRUE(adaptor->finalize().ok());
  return blocked;
}

// The columns that cut execute into phases: every `_ms` column but the writer thread's and the
// total. Found by name, so a column added later is held to the sum too.
bool stage_column(const std::string& name) {
  return name.ends_with("_ms") && name != "encode_ms" && name != "write_ms" && name != "blocked_ms";
}

struct StepSums {
  double stages_ms = 0, other_ms = 0;
  int rows = 0;
  std::vector<std::string> blocked_cells;  // blocked_ms of each row
};

std::map<int, StepSums> sums_per_step(const std::vector<std::vector<std::string>>& log) {
  std::map<int, StepSums> steps;
  const std::vector<std::string>& header = log.at(0);
  for (std::size_t row = 1; row < log.size(); ++row) {
    StepSums& s = steps[std::stoi(cell(log, row, "step"))];
    ++s.rows;
    s.blocked_cells.push_back(cell(log, row, "blocked_ms"));
    for (std::size_t c = 0; c < header.size(); ++c) {
      if (stage_column(header[c])) s.stages_ms += std::stod(log[row].at(c));
      if (header[c] == "other_ms") s.other_ms += std::stod(log[row].at(c));
    }
  }
  return steps;
}

// A step's rows: 2 orbit views + 3 scenes. The slack: each cell is rounded to 0.001 ms, so the
// sum of a step's 5 rows x 11 stage columns may be off by 0.03 ms; 0.3 ms leaves room for a
// column of a few microseconds the adaptor itself rounds, and is far below what a stage left
// out of the columns costs (an agreement, a probe pass, a hand-off: 0.1 ms to tens of ms).
constexpr int kRowsPerStep = 5;
constexpr double kRelative = 0.02;
constexpr double kSlackMs = 0.3;

TEST(LogAccounts, StageColumnsSumToTheBlockedTimeOfEachStep) {
  const SharedDir shared("log_accounts");
  const Blocked blocked = run(shared.path());
  if (rank() != 0) return;  // the writer rank's log and its own blocked time
  ASSERT_EQ(blocked.reported_ms.size(), static_cast<std::size_t>(kStepCount));
  const auto log = read_csv(shared.path() + "/tetray_log.csv");
  const std::map<int, StepSums> steps = sums_per_step(log);
  ASSERT_EQ(steps.size(), static_cast<std::size_t>(kStepCount));
  double other_ms = 0, all_ms = 0;
  for (const auto& [step, sums] : steps) {
    const double reported = blocked.reported_ms.at(static_cast<std::size_t>(step));
    EXPECT_EQ(sums.rows, kRowsPerStep) << "step " << step;
    EXPECT_LE(reported, blocked.around_call_ms.at(static_cast<std::size_t>(step)))
        << "step " << step << ": the adaptor's clock runs inside the call";
    EXPECT_NEAR(sums.stages_ms, reported, kRelative * reported + kSlackMs)
        << "step " << step << ": the stage columns miss "
        << 100 * (reported - sums.stages_ms) / reported << "% of the blocked time";
    for (const std::string& logged : sums.blocked_cells) {
      EXPECT_NE(logged, "<missing>") << "the log has no blocked_ms column";
      if (logged != "<missing>") {
        EXPECT_NEAR(std::stod(logged), reported, 0.0006) << "step " << step;
      }
    }
    other_ms += sums.other_ms;
    all_ms += reported;
  }
  // The remainder is what no stage claims: glue between stages, never a stage's work. Over all
  // steps well under half of the wait (a stage's work charged there would make it most of it).
  EXPECT_LT(other_ms, 0.25 * all_ms) << "other_ms " << other_ms << " of " << all_ms << " ms";
}

}  // namespace
}  // namespace tetray::testing
