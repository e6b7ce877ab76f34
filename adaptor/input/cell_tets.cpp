#include "adaptor/input/cell_tets.hpp"

#include <span>

#include "adaptor/input/cell_split.hpp"

namespace tetray {
namespace {

std::string shape_problem(const MeshView& mesh) {
  const CellsView& c = mesh.cells;
  if (mesh.tets.count > 0) {
    return "the mesh has both " + std::to_string(mesh.tets.count) + " tets and " +
           std::to_string(c.count) + " cells; pass one or the other";
  }
  if (mesh.points.count > 0 && mesh.points.xyz == nullptr) {
    return "mesh.points.xyz is null but points.count is " + std::to_string(mesh.points.count);
  }
  if (c.types == nullptr || c.offsets == nullptr) {
    return "mesh.cells.count is " + std::to_string(c.count) + " but its types or offsets are null";
  }
  return {};
}

// offsets and connectivity as int64, the connectivity's length read from offsets[count].
template <typename Index>
std::string widen(const CellsView& c, std::vector<std::int64_t>& offsets,
                  std::vector<std::int64_t>& connectivity) {
  const auto* in = static_cast<const Index*>(c.offsets);
  offsets.assign(in, in + c.count + 1);
  const std::int64_t length = offsets.back();
  if (length < 0 || (length > 0 && c.connectivity == nullptr)) {
    return "mesh.cells.offsets[count] is " + std::to_string(length) +
           (length < 0 ? "" : " but the connectivity is null");
  }
  const auto* ids = static_cast<const Index*>(c.connectivity);
  connectivity.assign(ids, ids + length);
  return {};
}

// The points' reference positions in double: the solver's own array when it is double, else a
// converted copy (held in `converted`).
std::span<const double> positions(const PointsView& points, std::vector<double>& converted) {
  const std::size_t values = 3 * points.count;
  if (points.type == ScalarType::float64) {
    return {static_cast<const double*>(points.xyz), values};
  }
  const auto* xyz = static_cast<const float*>(points.xyz);
  converted.assign(xyz, xyz + values);
  return converted;
}

}  // namespace

std::string CellTets::resolve(const MeshView& mesh, std::uint64_t topology_epoch, MeshView& out) {
  out = mesh;
  if (mesh.cells.count == 0) return {};
  if (topology_epoch != epoch_) {
    epoch_ = ~std::uint64_t{0};
    if (std::string error = split(mesh); !error.empty()) return error;
    epoch_ = topology_epoch;
  }
  out.tets = TetsView::of(std::span<const std::int64_t>(tets_));
  out.tets.ghost = ghost_.empty() ? nullptr : ghost_.data();
  out.cells = {};
  return {};
}

std::string CellTets::split(const MeshView& mesh) {
  tets_.clear();
  ghost_.clear();
  if (std::string error = shape_problem(mesh); !error.empty()) return error;
  const CellsView& c = mesh.cells;
  std::vector<std::int64_t> offsets, connectivity;
  std::string error = c.type == IndexType::int64 ? widen<std::int64_t>(c, offsets, connectivity)
                                                 : widen<std::int32_t>(c, offsets, connectivity);
  if (!error.empty()) return error;
  std::vector<double> converted;
  const std::span<const double> xyz = positions(mesh.points, converted);
  const std::vector<std::uint64_t> keys = position_keys(xyz);
  SplitCells split = split_cells(std::span(c.types, c.count), offsets, connectivity, keys, xyz);
  if (!split.error.empty()) return "mesh.cells: " + split.error;
  tets_ = std::move(split.tets);
  if (c.ghost != nullptr) {
    ghost_.resize(split.tet_cell.size());
    for (std::size_t t = 0; t < ghost_.size(); ++t) ghost_[t] = c.ghost[split.tet_cell[t]];
  }
  return {};
}

}  // namespace tetray
