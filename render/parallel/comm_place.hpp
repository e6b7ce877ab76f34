// This rank's place in a communicator, as the protocols ask for it: a protocol takes only the
// communicator, and on one rank does no MPI traffic beyond these two queries.
#pragma once

#include <mpi.h>

namespace tetray::render {

struct CommPlace {
  int rank = 0;
  int size = 1;
};

// Collective-free. Returns MPI_SUCCESS or the MPI error code.
inline int place_in(MPI_Comm comm, CommPlace& place) {
  if (const int rc = MPI_Comm_rank(comm, &place.rank); rc != MPI_SUCCESS) return rc;
  return MPI_Comm_size(comm, &place.size);
}

}  // namespace tetray::render
