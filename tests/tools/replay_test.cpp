// tetray-replay on a series this test writes: a .pvd of three .vtu steps of the plane scene
// whose isovalue field moves, and the same files given as a list.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "plane_scene.hpp"
#include "support/scratch_dir.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace tetray::testing {
namespace {

namespace fs = std::filesystem;

// Step k carries f = z - 0.5 k: the square z = 0.25 + 0.5 k, out of the box from k = 2 on.
std::vector<std::string> write_series(const ScratchDir& dir) {
  const PlaneScene scene = make_plane_scene(4);
  std::vector<std::string> files;
  std::ofstream pvd(dir / "series.pvd");
  pvd << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n";
  for (int k = 0; k < 3; ++k) {
    vtkio::TetGrid grid;
    grid.points = scene.mesh.points;
    grid.tets = scene.mesh.tets;
    for (double z : scene.f) grid.point_fields["f"].push_back(z - 0.5 * k);
    const std::string name = "step" + std::to_string(k) + ".vtu";
    std::string error;
    EXPECT_TRUE(vtkio::write_vtu(dir / name, grid, error)) << error;
    files.push_back(dir / name);
    pvd << "<DataSet timestep=\"" << 0.5 * k << "\" file=\"" << name << "\"/>\n";
  }
  pvd << "</Collection>\n</VTKFile>\n";
  return files;
}

std::string write_config(const ScratchDir& dir, const std::string& out) {
  const std::string path = dir / (out + ".yaml");
  std::ofstream(path) << plane_config(dir / out, ", formats: [png]");
  return path;
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

}  // namespace
}  // namespace tetray::testing
