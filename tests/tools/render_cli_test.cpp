// tetray-render end to end on small generated grids: a rendered image with hits, and a clear
// message with a nonzero exit for each kind of bad input.
#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdio>
#include <fstream>

#include "scenes/box_mesh.hpp"
#include "support/png_read.hpp"
#include "support/scratch_dir.hpp"
#include "support/text_edit.hpp"
#include "tools/vtk_io/vtk_files.hpp"

namespace tetray {
namespace {

using testing::ScratchDir;

struct CommandResult {
  int exit_code = -1;
  std::string output;  // stdout and stderr together
};

CommandResult run_render(const std::string& arguments) {
  const std::string command = std::string(TETRAY_RENDER_EXE) + " " + arguments + " 2>&1";
  CommandResult run;
  FILE* pipe = ::popen(command.c_str(), "r");
  if (!pipe) return run;
  char buffer[512];
  while (std::fgets(buffer, sizeof(buffer), pipe)) run.output += buffer;
  const int status = ::pclose(pipe);
  run.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// The gyroid-twist scene of docs/architecture.md §6 at n = 8 (3072 tets), field "gyroid".
std::string write_gyroid(const ScratchDir& dir) {
  const GyroidTwist scene = make_gyroid_twist(8, 0);
  vtkio::TetGrid grid;
  grid.points = scene.mesh.points;
  grid.tets = scene.mesh.tets;
  grid.point_fields["gyroid"] = scene.field;
  const std::string path = dir / "gyroid.vtu";
  std::string error;
  EXPECT_TRUE(vtkio::write_vtu(path, grid, error)) << error;
  return path;
}

std::size_t opaque_pixels(const testing::PngPixels& image) {
  std::size_t count = 0;
  for (std::size_t p = 3; p < image.rgba.size(); p += 4) count += image.rgba[p] > 0;
  return count;
}

TEST(RenderCli, RendersAGridToPngAndExr) {
  ScratchDir dir;
  const std::string grid = write_gyroid(dir);
  const CommandResult png = run_render(
      grid + " --field gyroid --iso 0 --iso 0.5 --size 96x64 --threads 2 -o " + dir / "out.png");
  ASSERT_EQ(png.exit_code, 0) << png.output;
  EXPECT_TRUE(contains(png.output, "96x64")) << png.output;
  EXPECT_TRUE(contains(png.output, "3072 tets")) << png.output;
  EXPECT_TRUE(contains(png.output, dir / "out.png")) << png.output;

  const testing::PngPixels image = testing::read_png_rgba8(dir / "out.png");
  ASSERT_TRUE(image.error.empty()) << image.error;
  EXPECT_EQ(image.width, 96);
  EXPECT_EQ(image.height, 64);
  // The gyroid level set crosses the whole cube, which the fitted camera shows entirely.
  EXPECT_GT(opaque_pixels(image), image.rgba.size() / 4 / 10);

  const CommandResult exr =
      run_render(grid +
                 " --field gyroid --iso=-0.25 --eye 2.5,1.8,3.2 --look-at 0,0,0 "
                 "--up 0,1,0 --fov 40 --size 32x32 -o " +
                 dir / "out.exr");
  ASSERT_EQ(exr.exit_code, 0) << exr.output;
  EXPECT_TRUE(std::filesystem::file_size(dir / "out.exr") > 0);
}

TEST(RenderCli, UnknownFieldListsTheAvailableOnes) {
  ScratchDir dir;
  const CommandResult run =
      run_render(write_gyroid(dir) + " --field temperature --iso 0 -o " + dir / "out.png");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_TRUE(contains(run.output, "'temperature'")) << run.output;
  EXPECT_TRUE(contains(run.output, "'gyroid'")) << run.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "out.png"));
}

TEST(RenderCli, MissingFileIsAnError) {
  ScratchDir dir;
  const CommandResult run =
      run_render(dir / "absent.vtu" + " --field f --iso 0 -o " + dir / "out.png");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_TRUE(contains(run.output, dir / "absent.vtu")) << run.output;
  EXPECT_TRUE(contains(run.output, "no such file")) << run.output;
}

TEST(RenderCli, BadOptionValuesAreErrors) {
  ScratchDir dir;
  const std::string grid = write_gyroid(dir);
  const std::string base = grid + " --field gyroid ";
  const std::pair<std::string, std::string> cases[] = {
      {base + "--iso 0 --size 0x10 -o x.png", "--size"},
      {base + "--iso 0 --size 64 -o x.png", "--size"},
      {base + "--iso 0 --eye 1,2 -o x.png", "--eye"},
      {base + "--iso 0 --packet 8x8 -o x.png", "--packet"},
      {base + "--iso 0 --threads 0 -o x.png", "--threads"},
      {base + "--iso 0 --fov 180 -o x.png", "--fov"},
      {base + "--iso 0 -o x.jpg", ".exr or .png"},
      {base + "--iso abc -o x.png", "--iso"},
      {base + "-o x.png", "--iso"},
      {base + "--iso 0 --fov nan -o x.png", "--fov"},
      {base + "--iso 0 --fov=-inf -o x.png", "--fov"},
      {base + "--iso 0 --eye 1,1,1 --look-at 1,1,1 -o " + dir / "x.png", "the same point"},
      {base + "--iso 0 --eye 0,5,0 --look-at 0,0,0 -o " + dir / "x.png", "parallel"},
      {base + "--iso 0 --up 0,0,0 -o " + dir / "x.png", "up must not be the zero vector"},
      {base + "--iso 0 --eye 3,2,1 --up 0,0,0 -o " + dir / "x.png",
       "up must not be the zero vector"},
      {base + "--iso 0 --up 1,0.7,1.3 -o " + dir / "x.png", "parallel"},
  };
  for (const auto& [arguments, mention] : cases) {
    const CommandResult run = run_render(arguments);
    EXPECT_NE(run.exit_code, 0) << arguments;
    EXPECT_TRUE(contains(run.output, mention)) << arguments << "\n" << run.output;
  }
  std::string many_isovalues;
  for (int k = 0; k < 17; ++k) many_isovalues += " --iso " + std::to_string(0.01 * k);
  const CommandResult run = run_render(base + many_isovalues + " -o x.png");
  EXPECT_NE(run.exit_code, 0);
  EXPECT_TRUE(contains(run.output, "at most 16")) << run.output;
}

// The camera's up is a direction at any scale, as in the config: [1e-300, 1e-300, 0] draws what
// [1, 1, 0] draws, and that view differs from the default up's.
TEST(RenderCli, ATinyUpIsADirection) {
  ScratchDir dir;
  const std::string base = write_gyroid(dir) + " --field gyroid --iso 0 --size 48x32 ";
  for (const char* up : {"1e-300,1e-300,0", "1,1,0", "0,1,0"}) {
    const CommandResult run =
        run_render(base + "--up " + up + " -o " + dir / (up + std::string(".png")));
    ASSERT_EQ(run.exit_code, 0) << up << "\n" << run.output;
  }
  const auto tiny = testing::read_png_rgba8(dir / "1e-300,1e-300,0.png");
  const auto unit = testing::read_png_rgba8(dir / "1,1,0.png");
  const auto y = testing::read_png_rgba8(dir / "0,1,0.png");
  EXPECT_GT(opaque_pixels(tiny), 48u * 32 / 10);
  EXPECT_EQ(tiny.rgba, unit.rgba);
  EXPECT_NE(tiny.rgba, y.rgba);
}

// A count attribute below zero took VTK's reader down with SIGSEGV; now an error names it.
TEST(RenderCli, ANegativeCellCountIsAnError) {
  ScratchDir dir;
  const std::string grid = write_gyroid(dir);
  const std::string text = testing::slurp(grid);
  ASSERT_NE(text.find("NumberOfCells=\""), std::string::npos);
  std::ofstream(dir / "negative.vtu", std::ios::binary)
      << testing::replaced_once(text, "NumberOfCells=\"", "NumberOfCells=\"-");
  const CommandResult run =
      run_render(dir / "negative.vtu" + " --field gyroid --iso 0 -o " + dir / "out.png");
  EXPECT_EQ(run.exit_code, 1) << run.output;  // an exit, not a signal
  EXPECT_TRUE(contains(run.output, "NumberOfCells=\"-")) << run.output;
  EXPECT_TRUE(contains(run.output, "a negative number")) << run.output;
}

}  // namespace
}  // namespace tetray
