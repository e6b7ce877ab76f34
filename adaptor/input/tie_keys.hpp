// The keys that break exact depth ties between tets (docs/architecture.md §3: equal depth goes
// to the smaller key). They must not depend on how the mesh is split among ranks, or the image
// would: the solver's global tet ids when it gives them (the fast path), else a hash of each
// tet's corner coordinates, which every partition computes alike for the same tet.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "tetray/adaptor.hpp"

namespace tetray {

// Fills `keys` (one per tet) from tets.global_ids, or from the corners that `connectivity`
// (4 per tet, int64) names in `points`. Returns an error when a global id does not fit 32 bits.
// A corner index outside the points is never read (the mesh check reports it later).
std::string tie_keys(const TetsView& tets, std::span<const std::int64_t> connectivity,
                     const PointsView& points, std::vector<std::uint32_t>& keys);

}  // namespace tetray
