// tetray-replay on a series this test writes: a .pvd of three .vtu steps of the plane scene
// whose isovalue field moves, and the same files given as a list; a series with a step that
// cannot be read, and one whose second scene's field is missing from a step.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "plane_scene.hpp"
#include "support/pvtu_summary.hpp"
#include "support/scratch_dir.hpp"
#include "support/text_edit.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

// Step k carries f = z - 0.5 k: the square z = 0.25 + 0.5 k, out of the box from k = 2 on.
vtkio::TetGrid moving_plane(const PlaneScene& scene, int k) {
  vtkio::TetGrid grid;
  grid.points = scene.mesh.points;
  grid.tets = scene.mesh.tets;
  for (double z : scene.f) grid.point_fields["f"].push_back(z - 0.5 * k);
  return grid;
}

// Three steps, the grid of step k from make(scene, k), as step<k>.vtu and series.pvd.
template <typename Make = decltype(&moving_plane)>
std::vector<std::string> write_series(const ScratchDir& dir, Make&& make = moving_plane) {
  const PlaneScene scene = make_plane_scene(4);
  std::vector<std::string> files;
  std::ofstream pvd(dir / "series.pvd");
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (int k = 0; k < 3; ++k) {
    const vtkio::TetGrid grid = make(scene, k);
    const std::string name = "step" + std::to_string(k) + ".vtu";
    std::string error;
    EXPECT_TRUE(vtkio::write_vtu(dir / name, grid, error)) << error;
    files.push_back(dir / name);
    pvd << "<DataSet timestep=\"" << 0.5 * k << "\" file=\"" << name << "\"/>\n";
  }
  pvd << "</Collection>\n</VTKFile>\n";
  return files;
}

std::string write_config(const ScratchDir& dir, const std::string& out,
                         const std::string& scene_lines = "") {
  const std::string path = dir / (out + ".yaml");
  std::ofstream(path) << plane_config(dir / out, ", formats: [png]", "", scene_lines);
  return path;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void expect_moving_plane(const std::string& log_path) {
  const auto log = read_csv(log_path);
  ASSERT_EQ(log.size(), 4u);
  const ExpectedHits expected = expected_plane_hits();
  EXPECT_GE(std::stoull(cell(log, 1, "hits")), expected.sure);
  EXPECT_GT(std::stoull(cell(log, 2, "hits")), 0u);      // z = 0.75: a larger square, nearer
  EXPECT_EQ(cell(log, 3, "hits"), "0");                  // z = 1.25: outside the mesh
  EXPECT_EQ(cell(log, 2, "bvh_update"), "field_refit");  // same topology: no rebuild
}

TEST(Replay, RendersAPvdSeries) {
  ScratchDir dir;
  write_series(dir);
  const std::string command = std::string(TETRAY_REPLAY) + " --config " + write_config(dir, "pvd") +
                              " " + (dir / "series.pvd");
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  expect_moving_plane(dir / "pvd/tetray_log.csv");
  EXPECT_EQ(cell(read_csv(dir / "pvd/tetray_log.csv"), 3, "time"), "1");
  EXPECT_TRUE(fs::exists(dir.path() / "pvd/plane/plane_000002.png"));
}

// --output writes where the config says nothing of; the config's own directory stays empty, and
// a config mistake is still reported with the config's name.
TEST(Replay, OutputOverridesTheConfigsDirectory) {
  ScratchDir dir;
  write_series(dir);
  const std::string config = write_config(dir, "configured");
  const std::string command = std::string(TETRAY_REPLAY) + " -c " + config + " --output " +
                              (dir / "elsewhere") + " " + (dir / "series.pvd");
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  expect_moving_plane(dir / "elsewhere/tetray_log.csv");
  EXPECT_TRUE(fs::exists(dir.path() / "elsewhere/plane/plane_000002.png"));
  EXPECT_FALSE(fs::exists(dir.path() / "configured"));

  std::ofstream(dir / "bad.yaml") << read_text(config) << "bogus_key: 1\n";
  const std::string bad = std::string(TETRAY_REPLAY) + " -c " + (dir / "bad.yaml") + " -o " +
                          (dir / "bad_out") + " " + (dir / "series.pvd") + " 2>" +
                          (dir / "bad.txt");
  EXPECT_EQ(std::system(bad.c_str()) >> 8, 2);
  const std::string message = read_text(dir / "bad.txt");
  EXPECT_NE(message.find("bad.yaml with --output"), std::string::npos) << message;
  EXPECT_NE(message.find("bogus_key"), std::string::npos) << message;
}

TEST(Replay, RendersAListOfFilesAndFailsOnAMissingOne) {
  ScratchDir dir;
  const auto files = write_series(dir);
  std::string command = std::string(TETRAY_REPLAY) + " -c " + write_config(dir, "list");
  for (const auto& f : files) command += " " + f;
  ASSERT_EQ(std::system(command.c_str()), 0) << command;
  expect_moving_plane(dir / "list/tetray_log.csv");
  const std::string missing = std::string(TETRAY_REPLAY) + " -c " + write_config(dir, "missing") +
                              " " + files[0] + " " + (dir / "nothing.vtu") + " 2>/dev/null";
  EXPECT_NE(std::system(missing.c_str()), 0);
  EXPECT_TRUE(fs::exists(dir.path() / "missing/plane/plane_000000.png"));
}

// Step 1 is not a VTK file: it fails, writes no image (before, it rendered a blank one from an
// empty grid), and the steps around it render.
TEST(Replay, AStepThatCannotBeReadWritesNoImage) {
  ScratchDir dir;
  write_series(dir);
  std::ofstream(dir / "step1.vtu") << "not a VTK file";
  const std::string command = std::string(TETRAY_REPLAY) + " -c " + write_config(dir, "out") + " " +
                              (dir / "series.pvd") + " 2>" + (dir / "stderr.txt");
  EXPECT_NE(std::system(command.c_str()), 0) << command;
  EXPECT_NE(read_text(dir / "stderr.txt").find("step1.vtu"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir.path() / "out/plane/plane_000000.png"));
  EXPECT_FALSE(fs::exists(dir.path() / "out/plane/plane_000001.png"));
  EXPECT_TRUE(fs::exists(dir.path() / "out/plane/plane_000002.png"));
  const auto log = read_csv(dir / "out/tetray_log.csv");
  ASSERT_EQ(log.size(), 3u);
  EXPECT_EQ(cell(log, 1, "step"), "0");
  EXPECT_EQ(cell(log, 2, "step"), "2");
}

// A second scene draws field h, which step 1 lacks: that scene is skipped there, with a
// message; the plane renders every step, and the replay succeeds.
TEST(Replay, ASceneWhoseFieldAStepLacksIsSkippedForThatStep) {
  ScratchDir dir;
  write_series(dir, [](const PlaneScene& scene, int k) {
    vtkio::TetGrid grid = moving_plane(scene, k);
    if (k != 1) grid.point_fields["h"] = scene.f;
    return grid;
  });
  const std::string h_scene =
      "  - {name: by_h, field: h, isovalues: [0.25], image: {width: 16, height: 16}}\n";
  const std::string command = std::string(TETRAY_REPLAY) + " -c " +
                              write_config(dir, "out", h_scene) + " " + (dir / "series.pvd") +
                              " 2>" + (dir / "stderr.txt");
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
  EXPECT_NE(read_text(dir / "stderr.txt")
                .find("step 1: scene 'by_h' skipped: field 'h' used by scene 'by_h' was not "
                      "passed to execute (passed: f)"),
            std::string::npos)
      << read_text(dir / "stderr.txt");
  for (int step = 0; step < 3; ++step) {
    const std::string digits = "00000" + std::to_string(step);
    EXPECT_TRUE(fs::exists(dir.path() / ("out/plane/plane_" + digits + ".png"))) << step;
    EXPECT_EQ(fs::exists(dir.path() / ("out/by_h/by_h_" + digits + ".png")), step != 1) << step;
  }
  const auto log = read_csv(dir / "out/tetray_log.csv");
  std::vector<std::string> rows;  // step and scene of each rendered image
  for (std::size_t row = 1; row < log.size(); ++row) {
    rows.push_back(cell(log, row, "step") + " " + cell(log, row, "scene"));
  }
  const std::vector<std::string> expected = {"0 plane", "0 by_h", "1 plane", "2 plane", "2 by_h"};
  EXPECT_EQ(rows, expected);
}

// Every due scene skipped (the series' field is named g, the config asks for f): nothing that
// was asked is written, so the replay fails and says which scene and why.
TEST(Replay, AStepThatRendersNoSceneFails) {
  ScratchDir dir;
  write_series(dir, [](const PlaneScene& scene, int k) {
    vtkio::TetGrid grid = moving_plane(scene, k);
    grid.point_fields["g"] = std::move(grid.point_fields["f"]);
    grid.point_fields.erase("f");
    return grid;
  });
  const std::string command = std::string(TETRAY_REPLAY) + " -c " + write_config(dir, "out") + " " +
                              (dir / "series.pvd") + " 2>" + (dir / "stderr.txt");
  EXPECT_EQ(std::system(command.c_str()) >> 8, 1) << command;
  const std::string message = read_text(dir / "stderr.txt");
  EXPECT_NE(message.find("step 0: no scene rendered: scene 'plane' skipped: field 'f'"),
            std::string::npos)
      << message;
  EXPECT_NE(message.find("(passed: g)"), std::string::npos) << message;
  EXPECT_FALSE(fs::exists(dir.path() / "out/plane/plane_000000.png"));
}

// The .pvtu of a run where one rank had no cells: its empty piece adds nothing, the other piece
// renders as the whole step would. A .pvtu whose every piece is empty says so and fails.
TEST(Replay, AnEmptyPieceAddsNothingAndAnAllEmptyFileSaysSo) {
  ScratchDir dir;
  const PlaneScene scene = make_plane_scene(4);
  std::string error;
  ASSERT_TRUE(vtkio::write_vtu(dir / "plane.vtu", moving_plane(scene, 0), error)) << error;
  vtkio::TetGrid empty;
  empty.point_fields["f"];
  ASSERT_TRUE(vtkio::write_vtu(dir / "empty.vtu", empty, error)) << error;
  const auto write_pvtu = [&](const std::string& name, const std::string& first) {
    std::ofstream(dir / name) << pvtu_summary({first, "empty.vtu"}, {"f"});
  };
  write_pvtu("half.pvtu", "plane.vtu");
  write_pvtu("none.pvtu", "empty.vtu");
  const std::string half =
      std::string(TETRAY_REPLAY) + " -c " + write_config(dir, "half") + " " + (dir / "half.pvtu");
  ASSERT_EQ(std::system(half.c_str()), 0) << half;
  const auto log = read_csv(dir / "half/tetray_log.csv");
  ASSERT_EQ(log.size(), 2u);
  EXPECT_GE(std::stoull(cell(log, 1, "hits")), expected_plane_hits().sure);

  const std::string none = std::string(TETRAY_REPLAY) + " -c " + write_config(dir, "none") + " " +
                           (dir / "none.pvtu") + " 2>" + (dir / "none.txt");
  EXPECT_EQ(std::system(none.c_str()) >> 8, 1) << none;
  const std::string message = read_text(dir / "none.txt");
  EXPECT_NE(message.find("none.pvtu': every piece is empty (no cells)"), std::string::npos)
      << message;
}

// A piece whose header declares a negative cell count took the replay down with SIGSEGV inside
// VTK; now the step fails with the cause.
TEST(Replay, ANegativeCellCountFailsTheStep) {
  ScratchDir dir;
  const auto files = write_series(dir);
  const std::string text = read_text(files[1]);
  ASSERT_NE(text.find("NumberOfCells=\""), std::string::npos);
  std::ofstream(files[1], std::ios::binary)
      << replaced_once(text, "NumberOfCells=\"", "NumberOfCells=\"-");
  const std::string command = std::string(TETRAY_REPLAY) + " -c " + write_config(dir, "out") + " " +
                              (dir / "series.pvd") + " 2>" + (dir / "stderr.txt");
  EXPECT_EQ(std::system(command.c_str()) >> 8, 1) << command;  // an exit, not a signal
  const std::string message = read_text(dir / "stderr.txt");
  EXPECT_NE(message.find("step1.vtu': <Piece> declares NumberOfCells=\"-"), std::string::npos)
      << message;
  EXPECT_TRUE(fs::exists(dir.path() / "out/plane/plane_000002.png"));
}

}  // namespace
}  // namespace tetray::testing
