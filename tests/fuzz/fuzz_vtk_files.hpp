// What the VTK fuzz targets share: a private directory holding a valid one-tet piece.vtu and a
// piece without cells, empty.vtu (a rank that had none), for their inputs to name; and the reading
// of a file, which must give a consistent grid or an error message (anything else aborts, which
// libFuzzer reports with the input).
#pragma once

#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>

#include "tools/vtk_io/vtk_files.hpp"

namespace tetray::fuzz {

// Created on first use, removed at exit.
inline const std::filesystem::path& fuzz_directory() {
  struct Directory {
    std::filesystem::path path =
        std::filesystem::temp_directory_path() / ("tetray_fuzz_" + std::to_string(::getpid()));
    Directory() {
      std::filesystem::create_directories(path);
      vtkio::TetGrid piece;
      piece.points = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
      piece.tets = {0, 1, 2, 3};
      piece.point_fields["f"] = {0, 1, 2, 3};
      std::string error;
      if (!vtkio::write_vtu((path / "piece.vtu").string(), piece, error)) std::abort();
      vtkio::TetGrid empty;
      empty.point_fields["f"];
      if (!vtkio::write_vtu((path / "empty.vtu").string(), empty, error)) std::abort();
    }
    ~Directory() {
      std::error_code ignored;
      std::filesystem::remove_all(path, ignored);
    }
  };
  static const Directory directory;
  return directory.path;
}

// An accepted grid must be consistent: whole tets, indices in range, one value per point.
inline void check_grid(const vtkio::TetGrid& grid) {
  const std::size_t points = grid.points.size() / 3;
  if (grid.points.size() % 3 != 0 || grid.tets.size() % 4 != 0) std::abort();
  for (const std::int64_t v : grid.tets) {
    if (v < 0 || static_cast<std::size_t>(v) >= points) std::abort();
  }
  for (const auto& [name, values] : grid.point_fields) {
    if (values.size() != points) std::abort();
  }
}

// Reads `path`: a consistent grid, or an error message.
inline void read_one(const std::string& path) {
  vtkio::TetGrid grid;
  std::string error;
  if (vtkio::read_grid(path, grid, error)) {
    check_grid(grid);
  } else if (error.empty()) {
    std::abort();
  }
}

}  // namespace tetray::fuzz
