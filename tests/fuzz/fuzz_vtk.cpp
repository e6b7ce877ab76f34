// The VTK readers on arbitrary bytes: VTK reads files, so each input is written to a file with
// the extension TETRAY_FUZZ_EXTENSION (.vtu, .pvtu or .pvd) in a private directory that also
// holds a valid piece, piece.vtu, and one without cells, empty.vtu (a rank that had none), for
// .pvtu and .pvd inputs to refer to. Every input must give a
// grid (or series) or an error message; a series' entries are read as replay reads them.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "tools/vtk_io/vtk_files.hpp"

namespace {

// The private directory, with piece.vtu and empty.vtu in it; removed at exit.
struct FuzzDirectory {
  std::filesystem::path path =
      std::filesystem::temp_directory_path() / ("tetray_fuzz_" + std::to_string(::getpid()));
  FuzzDirectory() {
    std::filesystem::create_directories(path);
    tetray::vtkio::TetGrid piece;
    piece.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
    piece.tets = {0, 1, 2, 3};
    piece.point_fields["f"] = {0, 1, 2, 3};
    std::string error;
    if (!tetray::vtkio::write_vtu((path / "piece.vtu").string(), piece, error)) std::abort();
    tetray::vtkio::TetGrid empty;
    empty.point_fields["f"];
    if (!tetray::vtkio::write_vtu((path / "empty.vtu").string(), empty, error)) std::abort();
  }
  ~FuzzDirectory() {
    std::error_code ignored;
    std::filesystem::remove_all(path, ignored);
  }
};

const std::filesystem::path& fuzz_directory() {
  static const FuzzDirectory directory;
  return directory.path;
}

// An accepted grid must be consistent: whole tets, indices in range, one value per point.
void check_grid(const tetray::vtkio::TetGrid& grid) {
  const std::size_t points = grid.points.size() / 3;
  if (grid.points.size() % 3 != 0 || grid.tets.size() % 4 != 0) std::abort();
  for (const std::int64_t v : grid.tets) {
    if (v < 0 || static_cast<std::size_t>(v) >= points) std::abort();
  }
  for (const auto& [name, values] : grid.point_fields) {
    if (values.size() != points) std::abort();
  }
}

void read_one(const std::string& path) {
  tetray::vtkio::TetGrid grid;
  std::string error;
  if (tetray::vtkio::read_grid(path, grid, error)) {
    check_grid(grid);
  } else if (error.empty()) {
    std::abort();
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = (fuzz_directory() / ("input" TETRAY_FUZZ_EXTENSION)).string();
  {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  if (std::string_view(TETRAY_FUZZ_EXTENSION) != ".pvd") {
    read_one(path);
    return 0;
  }
  std::vector<tetray::vtkio::SeriesEntry> series;
  std::string error;
  if (!tetray::vtkio::read_pvd(path, series, error)) {
    if (error.empty()) std::abort();
    return 0;
  }
  // The first few entries, as tetray-replay would read them (an entry naming the input
  // itself is a .pvd and is refused by read_grid).
  for (std::size_t k = 0; k < series.size() && k < 4; ++k) read_one(series[k].path);
  return 0;
}
