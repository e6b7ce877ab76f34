#include <cstddef>

#include "minisolver/comm.hpp"

namespace minisolver {

int MpiComm::rank() const {
  int r = 0;
  MPI_Comm_rank(comm_, &r);
  return r;
}

int MpiComm::size() const {
  int s = 1;
  MPI_Comm_size(comm_, &s);
  return s;
}

double MpiComm::sum(double local) const {
  double global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, comm_);
  return global;
}

double MpiComm::max(double local) const {
  double global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, comm_);
  return global;
}

void MpiComm::exchange(std::span<const int> peers, const std::vector<std::vector<double>>& send,
                       std::vector<std::vector<double>>& recv) const {
  constexpr int kTag = 7;
  std::vector<MPI_Request> requests(2 * peers.size());
  for (std::size_t i = 0; i < peers.size(); ++i) {
    MPI_Irecv(recv[i].data(), static_cast<int>(recv[i].size()), MPI_DOUBLE, peers[i], kTag, comm_,
              &requests[2 * i]);
    MPI_Isend(send[i].data(), static_cast<int>(send[i].size()), MPI_DOUBLE, peers[i], kTag, comm_,
              &requests[2 * i + 1]);
  }
  MPI_Waitall(static_cast<int>(requests.size()), requests.data(), MPI_STATUSES_IGNORE);
}

}  // namespace minisolver
