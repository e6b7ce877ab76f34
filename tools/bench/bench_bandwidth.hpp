// The memory-bandwidth bound of the update figures: the traffic a new time step's update must
// cause, and the time memcpy needs to move the same traffic on the same threads. Both the update
// and the memcpy are timed with cold caches (evict_caches before each run): in situ the solver's
// own step runs between two renders and leaves none of the renderer's data in cache, and a bound
// measured on buffers that fit in the last-level cache would be a cache bound, not a memory one.
//
// What is counted (bytes read + bytes written; an array updated in place counts in both, since
// its cache lines must be read before they are written back):
//   field only:      read  the solver's field array, the point -> vertex map, the leaf vertex
//                          lists and their offsets, the vertex store (f shares each 16-byte
//                          vertex with x, y, z) and the BVH nodes (links, then bounds);
//                    write the vertex store and the BVH nodes.
//   geometry+field:  read  the solver's points (and displacements) and field, the point ->
//                          vertex map, the leaf vertex lists and offsets, the BVH nodes;
//                    write the vertex store (whole vertices, no read needed) and the BVH nodes.
// The tets and tet ids are not read by an update.
#pragma once

#include <cstddef>
#include <functional>

#include "render/bvh/bvh.hpp"
#include "render/update/volume_update.hpp"

namespace tetray::bench {

struct UpdateTraffic {
  std::size_t read = 0;
  std::size_t written = 0;

  std::size_t total() const { return read + written; }
};

UpdateTraffic field_only_traffic(const render::TetVolume& volume, const render::Bvh& bvh,
                                 const render::FieldSource& field);
UpdateTraffic geometry_traffic(const render::TetVolume& volume, const render::Bvh& bvh,
                               const render::PointSource& points, const render::FieldSource& field);

// Reads a buffer several times the last-level cache, so the next timed run starts cold.
void evict_caches();

struct TimeAndBound {
  double work_ms = 0;   // best cold-cache time of the work
  double bound_ms = 0;  // best cold-cache time of a memcpy moving the same traffic
};

// Times `work` and a parallel memcpy of traffic.total()/2 bytes (memcpy reads and writes that
// many, so its traffic equals the work's) in alternation, each after evict_caches, and keeps
// the best of each: both see the same machine, which on a shared one is what makes their
// ratio meaningful.
TimeAndBound time_against_bound(const UpdateTraffic& traffic, const std::function<void()>& work);

}  // namespace tetray::bench
