// The solver's views as the renderer reads them: shape checks that need no pass over the data
// (null pointers, sizes, missing fields), and the conversions the renderer's interface needs
// (int32 connectivity to int64, global ids to 32-bit tie keys, ghost flags to a keep mask).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "render/parallel/global_reduce.hpp"
#include "render/update/volume_update.hpp"
#include "tetray/adaptor.hpp"

namespace tetray {

const FieldView* find_field(std::span<const FieldView> fields, std::string_view name);
// The field, or an empty view (a rank without points need not pass its fields).
FieldView field_or_empty(std::span<const FieldView> fields, std::string_view name);

// Empty when the mesh views are usable, else what is wrong with them.
std::string check_mesh_shape(const MeshView& mesh);

// Empty when `name` (used by `scene`) was passed, or the rank has no tets (nothing to render it
// on); else what is missing and which fields were passed.
std::string missing_field(std::span<const FieldView> fields, std::string_view name,
                          std::string_view scene, std::size_t tet_count);

// Empty when `name` was not passed or has one value per point.
std::string check_field_shape(std::span<const FieldView> fields, std::string_view name,
                              std::size_t point_count);

render::PointSource point_source(const PointsView& points);
render::FieldSource field_source(const FieldView& field);

// The connectivity as int64: the solver's own array when it is int64, else a converted copy
// in `scratch`.
std::span<const std::int64_t> connectivity_int64(const TetsView& tets,
                                                 std::vector<std::int64_t>& scratch);

// Widens `box` by the bounding box of the (reference) point coordinates.
void add_point_bounds(const PointsView& points, render::BoundingBox& box);

// Clears keep[t] for VTK ghost tets (DUPLICATECELL 1, HIDDENCELL 32).
void drop_ghost_tets(const std::uint8_t* ghost, std::vector<std::uint8_t>& keep);

}  // namespace tetray
