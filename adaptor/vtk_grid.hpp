// VTK unstructured grids of tets as plain arrays: the VTK bridge of the adaptor, tetray-render
// and tetray-replay read meshes through here. Cells other than tets are an error that names the
// cell type and the first offending cell.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

class vtkUnstructuredGrid;

namespace tetray::vtkio {

struct TetGrid {
  std::vector<double> points;                              // xyz interleaved
  std::vector<std::int64_t> tets;                          // 4 per tet
  std::vector<std::uint8_t> ghost;                         // vtkGhostType per tet, or empty
  std::map<std::string, std::vector<double>> point_fields; // scalar point arrays by name
};

// Converts an in-memory grid. Returns false and fills `error` on non-tet cells or
// multi-component point arrays that are requested by name but not scalar.
bool from_vtk(vtkUnstructuredGrid* grid, TetGrid& out, std::string& error);

// Reads a .vtu or .pvtu file (VTK XML readers).
bool read_grid(const std::string& path, TetGrid& out, std::string& error);

// The .vtu/.pvtu files and times listed by a ParaView .pvd collection, in time order.
struct SeriesEntry {
  double time = 0;
  std::string path;
};
bool read_pvd(const std::string& path, std::vector<SeriesEntry>& out, std::string& error);

// Writes a .vtu (binary, appended) — used by tests to make series, and by users to save steps.
bool write_vtu(const std::string& path, const TetGrid& grid, std::string& error);

}  // namespace tetray::vtkio
