#include "render/mesh_check.hpp"

#include <cmath>
#include <sstream>

#include "render/point_read.hpp"

namespace tetray::render {
namespace {

// Flags points with a non-finite coordinate (after displacement) or value; counts both kinds.
std::vector<std::uint8_t> flag_nonfinite_points(const PointSource& points, const FieldSource& field,
                                                MeshCheck& check, std::size_t& first_bad_point,
                                                std::size_t& first_bad_value) {
  std::vector<std::uint8_t> bad(points.count, 0);
  first_bad_point = first_bad_value = points.count;
  with_points(points, [&](const auto* xyz, const auto* disp) {
    for (std::size_t i = 0; i < points.count; ++i) {
      double p[3];
      point_position(xyz, disp, i, p);
      if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) continue;
      bad[i] = 1;
      ++check.nonfinite_points;
      first_bad_point = std::min(first_bad_point, i);
    }
  });
  if (field.values) {
    with_scalar(field.kind, [&](auto tag) {
      const auto* f = static_cast<const decltype(tag)*>(field.values);
      for (std::size_t i = 0; i < field.count; ++i) {
        if (std::isfinite(f[i])) continue;
        bad[i] = 1;
        ++check.nonfinite_values;
        first_bad_value = std::min(first_bad_value, i);
      }
    });
  }
  return bad;
}

std::string describe(const char* what, std::size_t index, std::uint64_t count) {
  std::ostringstream out;
  out << what << " at point " << index << " (" << count << " such point" << (count == 1 ? "" : "s")
      << "); policy is 'error'";
  return out.str();
}

}  // namespace

MeshCheck check_mesh(std::span<const std::int64_t> tets, const PointSource& points,
                     const FieldSource& field, NonFinitePolicy policy,
                     std::vector<std::uint8_t>& keep) {
  MeshCheck check;
  const std::size_t tet_count = tets.size() / 4;
  keep.assign(tet_count, 1);
  if (field.values && field.count != points.count) {
    check.error = "field has " + std::to_string(field.count) + " values for " +
                  std::to_string(points.count) + " points";
    return check;
  }
  if (points.count > static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max())) {
    check.error = "too many points on one rank (" + std::to_string(points.count) +
                  "); the renderer indexes points with 32 bits";
    return check;
  }
  const auto n = static_cast<std::int64_t>(points.count);
  for (std::size_t i = 0; i < tets.size(); ++i) {
    if (tets[i] >= 0 && tets[i] < n) continue;
    if (check.tets_out_of_range++ == 0) {
      check.error = "tet " + std::to_string(i / 4) + " has point index " + std::to_string(tets[i]) +
                    " outside [0, " + std::to_string(n) + ")";
    }
  }
  if (!check.error.empty()) return check;
  std::size_t first_bad_point, first_bad_value;
  const auto bad = flag_nonfinite_points(points, field, check, first_bad_point, first_bad_value);
  if (policy == NonFinitePolicy::error) {
    if (check.nonfinite_points)
      check.error = describe("non-finite coordinate", first_bad_point, check.nonfinite_points);
    else if (check.nonfinite_values)
      check.error = describe("non-finite field value", first_bad_value, check.nonfinite_values);
    return check;
  }
  for (std::size_t t = 0; t < tet_count; ++t) {
    for (int k = 0; k < 4; ++k) {
      if (!bad[tets[4 * t + k]]) continue;
      keep[t] = 0;
      ++check.tets_skipped;
      break;
    }
  }
  return check;
}

}  // namespace tetray::render
