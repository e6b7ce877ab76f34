// Per-vertex values of the vertices several ranks hold (a vertex on a face between two ranks'
// tets), combined over those ranks: the exact sums of smooth shading's gradients
// (render/update/vertex_gradients.hpp).
// Vertices are matched by exact position, since the solver's point numbers are per rank. Each
// vertex has a home rank (a hash of its position): the ranks send it their values, it combines
// them and sends the result back, so a rank sends and receives only its own shared vertices'.
#pragma once

#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

namespace tetray::render {

// A point's exact position (the caller's reference coordinates, -0 stored as +0).
struct PointKey {
  double x, y, z;
};

class SharedVertices {
 public:
  // Collective. `keys`: this rank's candidates (the vertices of its domain's boundary faces).
  // A candidate is shared when ranks other than this one hold its position too; a position that
  // one rank holds twice (duplicated points) is never shared, as no position can tell them apart.
  int build(std::span<const PointKey> keys, MPI_Comm comm);

  // The candidates (indices into build's keys) that are shared, in the order of the values below.
  const std::vector<std::uint32_t>& shared() const { return shared_; }

  // Collective. values[i * width, (i + 1) * width) belong to shared()[i]; each becomes the
  // maximum (the sum) over the ranks that hold the vertex. Return MPI_SUCCESS or the MPI error.
  int max(std::span<std::int16_t> values, std::size_t width) const;
  int sum(std::span<std::int32_t> values, std::size_t width) const;
  int sum(std::span<double> values, std::size_t width) const;

 private:
  template <typename T, typename Combine>
  int combine(std::span<T> values, std::size_t width, T identity, Combine op) const;

  MPI_Comm comm_ = MPI_COMM_NULL;
  std::vector<std::uint32_t> shared_;
  std::vector<int> send_counts_, send_offsets_;  // shared vertices per home rank (shared_ order)
  std::vector<int> recv_counts_, recv_offsets_;  // entries this rank is home for, per sender
  std::vector<std::uint32_t> slot_;              // per received entry, its vertex among them
  std::size_t slots_ = 0;
};

}  // namespace tetray::render
