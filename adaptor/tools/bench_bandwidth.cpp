#include "bench_bandwidth.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <vector>

#include "bench_timing.hpp"

namespace tetray::bench {
namespace {

constexpr std::size_t kChunkBytes = std::size_t{1} << 20;

std::size_t scalar_bytes(render::ScalarKind kind) {
  return kind == render::ScalarKind::f64 ? sizeof(double) : sizeof(float);
}

UpdateTraffic store_traffic(const render::TetVolume& volume, const render::Bvh& bvh) {
  return {
      volume.tets.size() * sizeof(render::Tet),
      volume.vertices.size() * sizeof(render::Vertex) + bvh.nodes.size() * sizeof(render::BvhNode)};
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

}  // namespace

UpdateTraffic field_only_traffic(const render::TetVolume& volume, const render::Bvh& bvh,
                                 const render::FieldSource& field) {
  UpdateTraffic traffic = store_traffic(volume, bvh);
  traffic.read += field.count * scalar_bytes(field.kind);
  return traffic;
}

UpdateTraffic geometry_traffic(const render::TetVolume& volume, const render::Bvh& bvh,
                               const render::PointSource& points,
                               const render::FieldSource& field) {
  UpdateTraffic traffic = field_only_traffic(volume, bvh, field);
  traffic.read += 3 * points.count * scalar_bytes(points.xyz_kind);
  return traffic;
}

double memcpy_bound_ms(const UpdateTraffic& traffic) {
  const std::size_t bytes = traffic.total() / 2;
  std::vector<std::byte> source(bytes, std::byte{1});
  std::vector<std::byte> destination(bytes);
  parallel_copy(destination.data(), source.data(), bytes);
  return best_ms(kRepetitions, [&] { parallel_copy(destination.data(), source.data(), bytes); });
}

}  // namespace tetray::bench
