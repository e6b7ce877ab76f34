// The VTK bridge: a solver that already holds its mesh as a vtkUnstructuredGrid of tets hands
// that to the adaptor. Point data arrays with one component become fields by name; the cell
// array vtkGhostType gives the ghost flags. Off-trigger steps read nothing from the grid.
#pragma once

#include <cstdint>

#include "tetray/adaptor.hpp"

class vtkUnstructuredGrid;

namespace tetray {

// Same contract as Adaptor::execute; a grid with cells other than tets is an invalid_argument
// that names the cell type and the first such cell.
Status execute(Adaptor& adaptor, std::int64_t step, double time, vtkUnstructuredGrid* grid,
               const Changes& changes = {}, ExecuteReport* report = nullptr);

}  // namespace tetray
