// tetray-scene end to end: the .vtu it writes reads back as the gyroid-twist scene it was made
// from (points, tets and the field, exactly: the file stores Float64), and a bad size is refused.
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "scenes/box_mesh.hpp"
#include "support/scratch_dir.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace tetray::testing {
namespace {

int run(const std::string& arguments) {
  return std::system(
      (std::string(TETRAY_SCENE_EXE) + " " + arguments + " > /dev/null 2>&1").c_str());
}

TEST(SceneWriter, WritesTheBenchmarkScene) {
  const ScratchDir dir;
  const std::string path = dir / "gyroid.vtu";
  ASSERT_EQ(run("--size 5 --time 0.7 -o " + path), 0);
  vtkio::TetGrid grid;
  std::string error;
  ASSERT_TRUE(vtkio::read_grid(path, grid, error)) << error;
  const GyroidTwist expected = make_gyroid_twist(5, 0.7);
  EXPECT_EQ(grid.points, expected.mesh.points);
  EXPECT_EQ(grid.tets, expected.mesh.tets);
  ASSERT_EQ(grid.point_fields.count("f"), 1u);
  EXPECT_EQ(grid.point_fields.at("f"), expected.field);
}

TEST(SceneWriter, RefusesABadSize) {
  const ScratchDir dir;
  EXPECT_NE(run("--size 0 -o " + std::string(dir / "x.vtu")), 0);
  EXPECT_NE(run("--size 5"), 0);  // no output
}

}  // namespace
}  // namespace tetray::testing
