#include "bench_bandwidth.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <limits>
#include <vector>

#include "bench_timing.hpp"

namespace tetray::bench {
namespace {

constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
constexpr std::size_t kMinEvictBytes = std::size_t{256} << 20;
// Cold runs are short next to the eviction, so more of them fit; the minimum of more runs is
// steadier on a shared machine.
constexpr int kColdRepetitions = 15;

std::size_t scalar_bytes(render::ScalarKind kind) {
  return kind == render::ScalarKind::f64 ? sizeof(double) : sizeof(float);
}

std::size_t bytes_of(const auto& items) { return items.size() * sizeof(items[0]); }

// What both kinds of update read: the field, the point -> vertex map, the leaf lists, and the
// nodes (their links), and write: the vertex store and the nodes.
UpdateTraffic common_traffic(const render::TetVolume& volume, const render::Bvh& bvh,
                             const render::FieldSource& field) {
  UpdateTraffic traffic;
  traffic.read = field.count * scalar_bytes(field.kind) + bytes_of(volume.point_vertex) +
                 bytes_of(bvh.leaf_vertex_begin) + bytes_of(bvh.leaf_vertices) +
                 bytes_of(bvh.nodes);
  traffic.written = bytes_of(volume.vertices) + bytes_of(bvh.nodes);
  return traffic;
}

void parallel_copy(std::byte* destination, const std::byte* source, std::size_t bytes) {
  const std::size_t chunks = (bytes + kChunkBytes - 1) / kChunkBytes;
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, chunks), [&](const auto& range) {
    for (std::size_t c = range.begin(); c < range.end(); ++c) {
      const std::size_t offset = c * kChunkBytes;
      std::memcpy(destination + offset, source + offset, std::min(kChunkBytes, bytes - offset));
    }
  });
}

std::size_t eviction_bytes() {
  const long l3 = sysconf(_SC_LEVEL3_CACHE_SIZE);
  return std::max(kMinEvictBytes, l3 > 0 ? 8 * static_cast<std::size_t>(l3) : std::size_t{0});
}

}  // namespace

UpdateTraffic field_only_traffic(const render::TetVolume& volume, const render::Bvh& bvh,
                                 const render::FieldSource& field) {
  UpdateTraffic traffic = common_traffic(volume, bvh, field);
  traffic.read += bytes_of(volume.vertices);  // f is written into lines that keep x, y, z
  return traffic;
}

UpdateTraffic geometry_traffic(const render::TetVolume& volume, const render::Bvh& bvh,
                               const render::PointSource& points,
                               const render::FieldSource& field) {
  UpdateTraffic traffic = common_traffic(volume, bvh, field);
  const std::size_t per_point =
      3 * scalar_bytes(points.xyz_kind) +
      (points.displacement ? 3 * scalar_bytes(points.displacement_kind) : 0);
  traffic.read += points.count * per_point;
  return traffic;
}

void evict_caches() {
  static std::vector<std::uint64_t> buffer(eviction_bytes() / sizeof(std::uint64_t), 1);
  const std::uint64_t sum = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, buffer.size()), std::uint64_t{0},
      [&](const auto& range, std::uint64_t s) {
        for (std::size_t i = range.begin(); i < range.end(); i += 8) s += buffer[i];
        return s;
      },
      [](std::uint64_t a, std::uint64_t b) { return a + b; });
  buffer[0] = sum & 1;  // keeps the reads
}

TimeAndBound time_against_bound(const UpdateTraffic& traffic, const std::function<void()>& work) {
  const std::size_t bytes = traffic.total() / 2;
  std::vector<std::byte> source(bytes, std::byte{1});
  std::vector<std::byte> destination(bytes);
  auto copy = [&] { parallel_copy(destination.data(), source.data(), bytes); };
  copy();
  TimeAndBound best{std::numeric_limits<double>::infinity(),
                    std::numeric_limits<double>::infinity()};
  for (int r = 0; r < kColdRepetitions; ++r) {
    best.work_ms = std::min(best.work_ms, best_ms(1, evict_caches, work));
    best.bound_ms = std::min(best.bound_ms, best_ms(1, evict_caches, copy));
  }
  return best;
}

}  // namespace tetray::bench
