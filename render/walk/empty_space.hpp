// Empty-space skipping for volume rendering (docs/architecture.md §8). A tet is empty for a
// volume scene when no stretch of a ray through it can add anything: the transfer function's
// opacity is zero over the tet's range of the field (TransferFunction::clear_over), and no
// isosurface of the scene lies within the tet's range of the surfaces' field. The walk crosses
// such tets without integrating them; where it would cross two empty tets in a row it jumps
// instead: the volume's BVH, with a flag per node saying whether any tet below is not empty,
// gives the first non-empty tet the ray enters beyond the empty one (next_busy_entry), found by
// the same exact entry test as a boundary face (entry_behind), so the walk goes on from there as
// from a new entry. An empty tet lets all light through and emits nothing, so the image differs
// from walking every tet only in how the runs of tets split into fragments (rounding, about
// 1e-16 relative, as between rank counts).
//
// Why flags and not the BVH's value ranges: a node's range covers its tets' values but not the
// surfaces' second field, and a flag per node is exact for each tet's own range while a node's
// range would keep every node whose range spans a clear interval between two opaque ones.
#pragma once

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/scene/iso_surface.hpp"
#include "render/walk/boundary_faces.hpp"
#include "render/walk/transfer_function.hpp"

namespace tetray::render {

// Which tets and BVH nodes hold anything for a volume scene, one byte each.
struct BusyTets {
  static constexpr std::uint8_t kEmpty = 0;
  static constexpr std::uint8_t kBusy = 1;
  // Empty, and so is every tet below a BVH node of two leaves or more that holds it: the gap a
  // ray crosses there is likely long.
  static constexpr std::uint8_t kEmptyRegion = 2;

  std::vector<std::uint8_t> tet;   // per TetVolume::tets
  std::vector<std::uint8_t> node;  // per Bvh::nodes: 1 when any tet below is busy
  std::size_t busy_count = 0;

  bool busy(std::uint32_t t) const { return tet[t] == kBusy; }
  bool in_empty_region(std::uint32_t t) const { return tet[t] == kEmptyRegion; }
};

// `surface_field`: the surfaces' field per vertex of the vertex store, or empty for the
// volume's own. Parallel over tets in the calling oneTBB arena.
BusyTets find_busy_tets(const TetVolume& volume, const Bvh& bvh, const TransferFunction& transfer,
                        std::span<const IsoSurface> surfaces, std::span<const float> surface_field);

// The first busy tet the ray enters at t >= t_from (ties at equal t to the smaller tet id), with
// the face it enters through (FaceEntry::face = kBoundaryFace) and the fields there.
std::optional<FaceEntry> next_busy_entry(const TetVolume& volume, const Bvh& bvh,
                                         const BusyTets& busy, const RayFrame& frame, double t_from,
                                         std::span<const float> second = {});

}  // namespace tetray::render
