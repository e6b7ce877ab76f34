// The global mesh a run starts from: the docs/architecture.md §6 box through tetray::make_box_mesh
// (the scene library shared with the benchmarks, scenes/), or the mini-solver's own beam and shell
// generators; the tets of the stiff region, if any, are material 1.
#pragma once

#include "minisolver/solver_config.hpp"

namespace minisolver {

Mesh make_mesh(const SolverConfig& config);

}  // namespace minisolver
