// The memory-bandwidth bound of issue 4: the bytes a new time step's update must touch, and the
// time memcpy needs to move the same amount of traffic on the same threads.
//
// What is counted, once each (the fused ingest reads every input byte once):
//   field only:      read  the solver's field array, the tets (4 x int32, to gather each tet's
//                          range); write the vertex store (f lives inside each 16-byte vertex,
//                          so every cache line of the store is rewritten) and the BVH nodes.
//   geometry+field:  read  the solver's points and field arrays, the tets;
//                    write the vertex store and the BVH nodes.
// Node reads during the bottom-up pass and the tet-id array (untouched) are not counted.
#pragma once

#include <cstddef>

#include "render/bvh.hpp"
#include "render/volume_update.hpp"

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

// Best time of a parallel memcpy of total/2 bytes in the calling arena: memcpy reads and writes
// that many, so its traffic equals the update's.
double memcpy_bound_ms(const UpdateTraffic& traffic);

}  // namespace tetray::bench
