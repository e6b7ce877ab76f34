// Checks of a solver's arrays before they enter the renderer. The renderer itself assumes
// valid input; the adaptor and tetray-render run these first and turn a finding into a status
// message (or, under the skip_tets policy, into a keep mask).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "render/core/value_bounds.hpp"  // kMaxCoordinate, kMaxFieldValue
#include "render/volume/point_source.hpp"

namespace tetray::render {

struct MeshCheck {
  std::string error;  // empty: usable (possibly after skipping tets)
  std::uint64_t tets_out_of_range = 0;
  std::uint64_t nonfinite_points = 0;  // NaN/Inf or beyond kMaxCoordinate
  std::uint64_t nonfinite_values = 0;  // NaN/Inf or beyond kMaxFieldValue
  std::uint64_t tets_skipped = 0;      // tets touching such a point or value
};

enum class NonFinitePolicy { error, skip_tets };

// Every index in [0, point_count), finite coordinates (with displacement) and field values
// within kMaxCoordinate and kMaxFieldValue. With skip_tets, tets touching a point or value
// that is not get keep[t] = 0 and are counted;
// with error the first finding is reported with its index. `keep` is resized to the tet count.
// `check_indices` false skips the index pass (the caller checked these tets against this point
// count before: it is most of the cost, 32 bytes per tet); indices are still never trusted
// for a memory access (an out-of-range one only marks its tet skipped).
MeshCheck check_mesh(std::span<const std::int64_t> tets, const PointSource& points,
                     const FieldSource& field, NonFinitePolicy policy,
                     std::vector<std::uint8_t>& keep, bool check_indices = true);

}  // namespace tetray::render
