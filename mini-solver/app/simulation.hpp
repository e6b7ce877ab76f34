// A coupled run: the solver section sets up the mesh and physics, the tetray section the
// adaptor; every step advances heat and elasticity and hands the rank's own tets, the
// displacement and the point fields to the adaptor. Returns the process exit code.
#pragma once

#include <mpi.h>

#include <string>

namespace minisolver {

enum ExitCode {
  exit_ok = 0,
  exit_config = 1,
  exit_refused = 2,
  exit_stopped = 3,
  exit_adaptor = 4
};

int run_simulation(const std::string& config_path, MPI_Comm comm);

}  // namespace minisolver
