#include "render/parallel/step_reductions.hpp"

#include <algorithm>

#include "render/parallel/comm_place.hpp"

namespace tetray::render {
namespace {

constexpr std::size_t kRangesPerScene = 5;    // box x, y, z, color, then cap
constexpr std::size_t kCountersPerScene = 4;  // tets, kept, skipped, bytes

int reduce_to_root(std::span<std::uint64_t> values, MPI_Op op, int root, MPI_Comm comm) {
  CommPlace place;
  if (const int rc = place_in(comm, place); rc != MPI_SUCCESS) return rc;
  if (place.size == 1 || values.empty()) return MPI_SUCCESS;
  void* send = place.rank == root ? MPI_IN_PLACE : values.data();
  return MPI_Reduce(send, values.data(), static_cast<int>(values.size()), MPI_UINT64_T, op, root,
                    comm);
}

}  // namespace

void StepRanges::clear() {
  points = {};
  std::fill(scenes.begin(), scenes.end(), SceneRanges{});
}

std::vector<ValueRange> pack(const StepRanges& ranges) {
  std::vector<ValueRange> packed(std::begin(ranges.points.axis), std::end(ranges.points.axis));
  packed.reserve(3 + kRangesPerScene * ranges.scenes.size());
  for (const SceneRanges& scene : ranges.scenes) {
    packed.insert(packed.end(), std::begin(scene.box.axis), std::end(scene.box.axis));
    packed.push_back(scene.color);
    packed.push_back(scene.cap);
  }
  return packed;
}

void unpack(std::span<const ValueRange> packed, StepRanges& ranges) {
  std::copy_n(packed.begin(), 3, std::begin(ranges.points.axis));
  for (std::size_t k = 0; k < ranges.scenes.size(); ++k) {
    const auto scene = packed.subspan(3 + kRangesPerScene * k, kRangesPerScene);
    std::copy_n(scene.begin(), 3, std::begin(ranges.scenes[k].box.axis));
    ranges.scenes[k].color = scene[3];
    ranges.scenes[k].cap = scene[4];
  }
}

std::vector<std::uint64_t> pack(std::span<const SceneCounters> counters) {
  std::vector<std::uint64_t> packed;
  packed.reserve(kCountersPerScene * counters.size());
  for (const SceneCounters& c : counters) {
    packed.insert(packed.end(), {c.tets, c.kept_tets, c.skipped_tets, c.bytes});
  }
  return packed;
}

void unpack(std::span<const std::uint64_t> packed, std::span<SceneCounters> counters) {
  for (std::size_t k = 0; k < counters.size(); ++k) {
    const auto c = packed.subspan(kCountersPerScene * k, kCountersPerScene);
    counters[k] = {c[0], c[1], c[2], c[3]};
  }
}

int sum_counters_to_root(std::span<SceneCounters> counters, int root, MPI_Comm comm) {
  std::vector<std::uint64_t> packed = pack(counters);
  const int rc = reduce_to_root(packed, MPI_SUM, root, comm);
  unpack(packed, counters);
  return rc;
}

int max_to_root(std::uint64_t& value, int root, MPI_Comm comm) {
  return reduce_to_root(std::span(&value, 1), MPI_MAX, root, comm);
}

int or_over_ranks(std::span<std::uint8_t> flags, MPI_Comm comm) {
  return MPI_Allreduce(MPI_IN_PLACE, flags.data(), static_cast<int>(flags.size()), MPI_UINT8_T,
                       MPI_BOR, comm);
}

}  // namespace tetray::render
