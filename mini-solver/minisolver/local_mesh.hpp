// One rank's share of a partitioned mesh: its own tets, the points they touch (owned, or ghosts
// owned by a lower rank that shares them), and the halo: for every neighbor rank, the shared
// points in ascending global id, the same order on both sides.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "minisolver/comm.hpp"
#include "minisolver/mesh.hpp"

namespace minisolver {

struct HaloNeighbor {
  int rank = 0;
  std::vector<std::int32_t> points;  // local point indices shared with `rank`
};

struct LocalMesh {
  std::vector<double> points;           // local points, xyz interleaved
  std::vector<std::int64_t> point_ids;  // global point ids, ascending
  std::vector<std::uint8_t> faces;      // per local point: Face bits
  std::vector<std::uint8_t> owned;      // per local point: 1 when this rank owns it
  std::vector<std::int32_t> tets;       // 4 local point indices per tet
  std::vector<std::int64_t> tet_ids;    // global tet ids
  std::vector<std::int32_t> material;   // per tet
  std::vector<HaloNeighbor> halo;       // ascending rank

  std::size_t point_count() const { return point_ids.size(); }
  std::size_t tet_count() const { return tet_ids.size(); }
  Vec3 point(std::size_t i) const { return {points[3 * i], points[3 * i + 1], points[3 * i + 2]}; }
  std::array<Vec3, 4> tet_points(std::size_t t) const {
    return {point(tets[4 * t]), point(tets[4 * t + 1]), point(tets[4 * t + 2]),
            point(tets[4 * t + 3])};
  }
};

// The share of `rank` given the part of every tet.
LocalMesh make_local_mesh(const Mesh& mesh, std::span<const std::int32_t> part, int rank);

// Partitions `mesh` by coordinate bisection over the ranks of `comm` and returns this rank's share.
LocalMesh distribute(const Mesh& mesh, const Comm& comm, std::span<const double> weights = {});

}  // namespace minisolver
