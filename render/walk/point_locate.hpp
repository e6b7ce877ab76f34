// Locating a point in a rank's tets through the volume's BVH (Aman et al. 2022, §4.2 locates by
// walking; the min/max BVH is already there and needs no start tet): the tet containing it and
// its barycentric coordinates, for probes. A point on a vertex, to the vertex store's float
// precision, gets exactly that vertex's weight 1, so a probe there reads the vertex's value.
#pragma once

#include <array>
#include <cstdint>
#include <optional>

#include "render/bvh/bvh.hpp"
#include "render/volume/tet_volume.hpp"
#include "render/walk/face_adjacency.hpp"

namespace tetray::render {

struct PointLocation {
  std::uint32_t tet = 0;           // index into volume.tets
  std::array<double, 4> weight{};  // of volume.tets[tet].v[0..3], summing to 1
};

// The tet containing `local` (the volume's local coordinates), allowing 1e-10 of its size
// outside for points on faces; of several, the one with the smallest tet_ids entry, so the
// answer does not depend on the BVH's layout. Empty outside every tet.
std::optional<PointLocation> locate_point(const TetVolume& volume, const Bvh& bvh, Vec3d local);

// Whether the point can lie in a tet of the BVH at all: inside its root box (with the slack of
// the inside test); locate_point finds nothing elsewhere.
bool within_bounds(const Bvh& bvh, Vec3d local);

// The point's location in tet `tet` when it lies strictly inside it (farther than the slack
// above from every face), where no other tet of a valid mesh contains it, so locate_point would
// give the same answer: a cheap first try for a point near the last one located.
std::optional<PointLocation> locate_strictly_inside(const TetVolume& volume, std::uint32_t tet,
                                                    Vec3d local);

// The same from tet `from` near the point: walks across the face the point lies furthest
// outside of (the neighbour from the face adjacency), at most kLocateWalkSteps tets, to a tet
// holding the point strictly inside; empty when the walk leaves this rank's tets, meets a
// degenerate tet, runs out of steps or ends with the point on a face (then ask locate_point).
inline constexpr int kLocateWalkSteps = 8;
std::optional<PointLocation> locate_by_walking(const TetVolume& volume,
                                               const FaceAdjacency<Tet20>& adjacency,
                                               std::uint32_t from, Vec3d local);

}  // namespace tetray::render
