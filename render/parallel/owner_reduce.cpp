#include "render/parallel/owner_reduce.hpp"

#include <vector>

namespace tetray::render {

int gather_from_lowest_holder(std::span<std::uint8_t> held, std::span<double> values,
                              std::size_t width, int root, MPI_Comm comm) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<int> owner(held.size());
  for (std::size_t i = 0; i < held.size(); ++i) owner[i] = held[i] ? rank : size;
  int rc = MPI_Allreduce(MPI_IN_PLACE, owner.data(), static_cast<int>(owner.size()), MPI_INT,
                         MPI_MIN, comm);
  if (rc != MPI_SUCCESS) return rc;
  // Only the owner contributes, so the sum is its answer exactly.
  for (std::size_t i = 0; i < held.size(); ++i) {
    if (owner[i] == rank) continue;
    for (std::size_t k = 0; k < width; ++k) values[i * width + k] = 0;
  }
  void* send = rank == root ? MPI_IN_PLACE : static_cast<void*>(values.data());
  rc = MPI_Reduce(send, values.data(), static_cast<int>(values.size()), MPI_DOUBLE, MPI_SUM, root,
                  comm);
  if (rc != MPI_SUCCESS) return rc;
  for (std::size_t i = 0; i < held.size(); ++i) held[i] = owner[i] < size;
  return MPI_SUCCESS;
}

}  // namespace tetray::render
