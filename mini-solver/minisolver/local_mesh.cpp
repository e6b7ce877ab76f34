#include "minisolver/local_mesh.hpp"

#include <algorithm>
#include <limits>

#include "minisolver/partition.hpp"

namespace minisolver {
namespace {

// Lowest and highest part touching each point; they differ only on part boundaries.
struct PointParts {
  std::vector<std::int32_t> lowest, highest;
};

PointParts point_parts(const Mesh& mesh, std::span<const std::int32_t> part) {
  PointParts p{
      std::vector<std::int32_t>(mesh.point_count(), std::numeric_limits<std::int32_t>::max()),
      std::vector<std::int32_t>(mesh.point_count(), -1)};
  for (std::size_t t = 0; t < mesh.tet_count(); ++t)
    for (int c = 0; c < 4; ++c) {
      const auto v = static_cast<std::size_t>(mesh.tets[4 * t + c]);
      p.lowest[v] = std::min(p.lowest[v], part[t]);
      p.highest[v] = std::max(p.highest[v], part[t]);
    }
  return p;
}

void take_own_tets(const Mesh& mesh, std::span<const std::int32_t> part, int rank,
                   std::vector<std::int32_t>& local_of_global, LocalMesh& local) {
  std::vector<std::int64_t> used;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (part[t] != rank) continue;
    local.tet_ids.push_back(static_cast<std::int64_t>(t));
    local.material.push_back(mesh.material[t]);
    used.insert(used.end(), mesh.tets.begin() + 4 * t, mesh.tets.begin() + 4 * t + 4);
  }
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());
  local.point_ids = used;
  for (std::size_t i = 0; i < used.size(); ++i)
    local_of_global[used[i]] = static_cast<std::int32_t>(i);
  for (const std::int64_t t : local.tet_ids)
    for (int c = 0; c < 4; ++c) local.tets.push_back(local_of_global[mesh.tets[4 * t + c]]);
}

// For every shared local point, every other part touching it becomes a halo neighbor.
void build_halo(const Mesh& mesh, std::span<const std::int32_t> part, int rank,
                const PointParts& parts, const std::vector<std::int32_t>& local_of_global,
                LocalMesh& local) {
  std::vector<std::pair<std::int32_t, std::int32_t>> sharing;  // (neighbor rank, local point)
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    if (part[t] == rank) continue;
    for (int c = 0; c < 4; ++c) {
      const auto v = static_cast<std::size_t>(mesh.tets[4 * t + c]);
      if (parts.lowest[v] != parts.highest[v] && local_of_global[v] >= 0)
        sharing.emplace_back(part[t], local_of_global[v]);
    }
  }
  std::sort(sharing.begin(), sharing.end());
  sharing.erase(std::unique(sharing.begin(), sharing.end()), sharing.end());
  for (const auto& [neighbor, point] : sharing) {
    if (local.halo.empty() || local.halo.back().rank != neighbor)
      local.halo.push_back({neighbor, {}});
    local.halo.back().points.push_back(point);
  }
}

}  // namespace

LocalMesh make_local_mesh(const Mesh& mesh, std::span<const std::int32_t> part, int rank) {
  LocalMesh local;
  std::vector<std::int32_t> local_of_global(mesh.point_count(), -1);
  take_own_tets(mesh, part, rank, local_of_global, local);
  const PointParts parts = point_parts(mesh, part);
  for (const std::int64_t g : local.point_ids) {
    const Vec3 x = mesh.point(static_cast<std::size_t>(g));
    local.points.insert(local.points.end(), x.begin(), x.end());
    local.faces.push_back(mesh.faces[g]);
    local.owned.push_back(parts.lowest[g] == rank ? 1 : 0);
  }
  build_halo(mesh, part, rank, parts, local_of_global, local);
  return local;
}

LocalMesh distribute(const Mesh& mesh, const Comm& comm, std::span<const double> weights) {
  const std::vector<std::int32_t> part = partition_rcb(mesh, comm.size(), weights);
  return make_local_mesh(mesh, part, comm.rank());
}

}  // namespace minisolver
