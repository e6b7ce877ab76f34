#include "render/parallel/global_reduce.hpp"

#include <algorithm>
#include <vector>

namespace tetray::render {

int global_ranges(std::span<ValueRange> ranges, MPI_Comm comm) {
  // Minimising the lows and the negated highs makes the union a single MPI_MIN reduction.
  std::vector<double> minima;
  minima.reserve(2 * ranges.size());
  for (const ValueRange& range : ranges) {
    minima.push_back(range.lo);
    minima.push_back(-range.hi);
  }
  const int error = MPI_Allreduce(MPI_IN_PLACE, minima.data(), static_cast<int>(minima.size()),
                                  MPI_DOUBLE, MPI_MIN, comm);
  if (error != MPI_SUCCESS) return error;
  for (std::size_t k = 0; k < ranges.size(); ++k) ranges[k] = {minima[2 * k], -minima[2 * k + 1]};
  return MPI_SUCCESS;
}

int global_bounds_and_ranges(BoundingBox& box, std::span<ValueRange> ranges, MPI_Comm comm) {
  std::vector<ValueRange> all(std::begin(box.axis), std::end(box.axis));
  all.insert(all.end(), ranges.begin(), ranges.end());
  const int error = global_ranges(all, comm);
  if (error != MPI_SUCCESS) return error;
  std::copy(all.begin(), all.begin() + 3, std::begin(box.axis));
  std::copy(all.begin() + 3, all.end(), ranges.begin());
  return MPI_SUCCESS;
}

}  // namespace tetray::render
