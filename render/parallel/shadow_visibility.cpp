#include "render/parallel/shadow_visibility.hpp"

#include <algorithm>
#include <climits>
#include <cstddef>

namespace tetray::render {
namespace {

// MPI counts are int: large buffers go in slices.
constexpr std::size_t kSlice = INT_MAX / 2;

template <typename Call>
int in_slices(std::size_t size, Call&& call) {
  for (std::size_t first = 0; first < size; first += kSlice) {
    const int rc = call(first, static_cast<int>(std::min(kSlice, size - first)));
    if (rc != MPI_SUCCESS) return rc;
  }
  return MPI_SUCCESS;
}

}  // namespace

int share_composited_depth(std::span<float> depth, int root, MPI_Comm comm) {
  return in_slices(depth.size(), [&](std::size_t first, int count) {
    return MPI_Bcast(depth.data() + first, count, MPI_FLOAT, root, comm);
  });
}

int combine_occlusion(std::span<std::uint8_t> occluded, int root, MPI_Comm comm) {
  int rank = 0;
  if (const int rc = MPI_Comm_rank(comm, &rank); rc != MPI_SUCCESS) return rc;
  return in_slices(occluded.size(), [&](std::size_t first, int count) {
    std::uint8_t* data = occluded.data() + first;
    return rank == root
               ? MPI_Reduce(MPI_IN_PLACE, data, count, MPI_UNSIGNED_CHAR, MPI_BOR, root, comm)
               : MPI_Reduce(data, nullptr, count, MPI_UNSIGNED_CHAR, MPI_BOR, root, comm);
  });
}

}  // namespace tetray::render
