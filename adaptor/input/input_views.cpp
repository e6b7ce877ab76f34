#include "adaptor/input/input_views.hpp"

#include <algorithm>
#include <limits>

namespace tetray {
namespace {

render::ScalarKind kind_of(ScalarType type) {
  return type == ScalarType::float32 ? render::ScalarKind::f32 : render::ScalarKind::f64;
}

// Ghost flags that mean "not rendered here" (vtkDataSetAttributes::DUPLICATECELL, HIDDENCELL).
constexpr std::uint8_t kGhostMask = 1 | 32;

}  // namespace

const FieldView* find_field(std::span<const FieldView> fields, std::string_view name) {
  for (const FieldView& f : fields) {
    if (f.name == name) return &f;
  }
  return nullptr;
}

FieldView field_or_empty(std::span<const FieldView> fields, std::string_view name) {
  const FieldView* field = find_field(fields, name);
  if (field != nullptr) return *field;
  FieldView empty;
  empty.name = name;
  return empty;
}

std::string check_mesh_shape(const MeshView& mesh) {
  constexpr auto kMaxPoints = static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max());
  constexpr auto kMaxTets = static_cast<std::size_t>(std::numeric_limits<std::uint32_t>::max());
  const PointsView& p = mesh.points;
  const TetsView& t = mesh.tets;
  if (p.count > 0 && p.xyz == nullptr) {
    return "mesh.points.xyz is null but points.count is " + std::to_string(p.count);
  }
  if (t.count > 0 && t.connectivity == nullptr) {
    return "mesh.tets.connectivity is null but tets.count is " + std::to_string(t.count);
  }
  if (p.count > kMaxPoints) {
    return "mesh.points.count " + std::to_string(p.count) + " exceeds 2^31-1 points per rank";
  }
  if (t.count > kMaxTets) {
    return "mesh.tets.count " + std::to_string(t.count) + " exceeds 2^32-1 tets per rank";
  }
  if (t.count > 0 && p.count == 0) {
    return "mesh has " + std::to_string(t.count) + " tets but no points";
  }
  return {};
}

std::string missing_field(std::span<const FieldView> fields, std::string_view name,
                          std::string_view scene, std::size_t tet_count) {
  if (tet_count == 0 || find_field(fields, name) != nullptr) return {};
  std::string passed;
  for (const FieldView& f : fields) passed += (passed.empty() ? "" : ", ") + std::string(f.name);
  return "field '" + std::string(name) + "' used by scene '" + std::string(scene) +
         "' was not passed to execute (passed: " + (passed.empty() ? "none" : passed) + ")";
}

std::string check_field_shape(std::span<const FieldView> fields, std::string_view name,
                              std::size_t point_count) {
  const FieldView* field = find_field(fields, name);
  if (field == nullptr) return {};
  if (field->count != point_count) {
    return "field '" + std::string(name) + "' has " + std::to_string(field->count) +
           " values but the mesh has " + std::to_string(point_count) + " points";
  }
  if (field->count > 0 && field->values == nullptr) {
    return "field '" + std::string(name) + "' has a null values pointer";
  }
  return {};
}

render::PointSource point_source(const PointsView& points) {
  return {points.xyz, kind_of(points.type), points.displacement, kind_of(points.displacement_type),
          points.count};
}

render::FieldSource field_source(const FieldView& field) {
  return {field.values, kind_of(field.type), field.count};
}

std::span<const std::int64_t> connectivity_int64(const TetsView& tets,
                                                 std::vector<std::int64_t>& scratch) {
  const std::size_t n = 4 * tets.count;
  if (tets.type == IndexType::int64) {
    return {static_cast<const std::int64_t*>(tets.connectivity), n};
  }
  const auto* in = static_cast<const std::int32_t*>(tets.connectivity);
  scratch.assign(in, in + n);
  return scratch;
}

void add_point_bounds(const PointsView& points, render::BoundingBox& box) {
  const std::size_t n = 3 * points.count;
  box.merge(points.type == ScalarType::float32
                ? render::local_bounds(std::span(static_cast<const float*>(points.xyz), n))
                : render::local_bounds(std::span(static_cast<const double*>(points.xyz), n)));
}

void drop_ghost_tets(const std::uint8_t* ghost, std::vector<std::uint8_t>& keep) {
  if (ghost == nullptr) return;
  for (std::size_t t = 0; t < keep.size(); ++t) {
    if (ghost[t] & kGhostMask) keep[t] = 0;
  }
}

}  // namespace tetray
