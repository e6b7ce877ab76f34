// The VTK bridge: a solver that already holds its mesh as a vtkUnstructuredGrid of tets hands
// that to the adaptor. Point data arrays with one component become fields by name; the cell
// array vtkGhostType gives the ghost flags. Off-trigger steps read nothing from the grid.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "tetray/adaptor.hpp"

class vtkUnstructuredGrid;

namespace tetray {

namespace vtkio {

// A VTK grid of tets as plain arrays: what the bridge reads from a vtkUnstructuredGrid.
struct TetGrid {
  std::vector<double> points;                               // xyz interleaved
  std::vector<std::int64_t> tets;                           // 4 per tet
  std::vector<std::uint8_t> ghost;                          // vtkGhostType per tet, or empty
  std::map<std::string, std::vector<double>> point_fields;  // scalar point arrays by name
};

// Converts an in-memory grid, splitting hexahedra, wedges, pyramids and quadratic cells into tets
// (README "Cells other than tets"). Returns false and fills `error` on cells it cannot split
// (naming the cell type and the first such cell).
bool from_vtk(vtkUnstructuredGrid* grid, TetGrid& out, std::string& error);

}  // namespace vtkio

// Same contract as Adaptor::execute; a grid with cells other than tets is an invalid_argument
// that names the cell type and the first such cell.
Status execute(Adaptor& adaptor, std::int64_t step, double time, vtkUnstructuredGrid* grid,
               const Changes& changes = {}, ExecuteReport* report = nullptr);

// Adaptor::execute with views of a grid already converted (from_vtk), e.g. one read from a file.
Status execute(Adaptor& adaptor, std::int64_t step, double time, const vtkio::TetGrid& grid,
               const Changes& changes = {}, ExecuteReport* report = nullptr);

}  // namespace tetray
