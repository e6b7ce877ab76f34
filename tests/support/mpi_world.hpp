// This process's place in MPI_COMM_WORLD, for the tests run under mpirun.
#pragma once

#include <mpi.h>

namespace tetray::render::testing {

struct World {
  int rank = 0;
  int size = 1;
};

inline World world() {
  World w;
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size);
  return w;
}

}  // namespace tetray::render::testing
