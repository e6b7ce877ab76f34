// Views of an in-memory vtkio::TetGrid for Adaptor::execute: shared by the VTK bridge and by
// tetray-replay, which both hold a grid converted from VTK.
#pragma once

#include <cstdint>

#include "tetray/adaptor.hpp"
#include "vtk_grid.hpp"

namespace tetray {

Status execute_grid(Adaptor& adaptor, std::int64_t step, double time, const vtkio::TetGrid& grid,
                    const Changes& changes, ExecuteReport* report);

}  // namespace tetray
