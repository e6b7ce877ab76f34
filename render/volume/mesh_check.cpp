#include "render/volume/mesh_check.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "render/volume/point_read.hpp"

namespace tetray::render {
namespace {

// How many of [0, n) satisfy a predicate, and the first that does (n when none): the shape of
// every check here, run in parallel.
struct Findings {
  std::uint64_t count = 0;
  std::size_t first = std::numeric_limits<std::size_t>::max();
};

template <typename Pred>
Findings find_all(std::size_t n, Pred&& found) {
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, n), Findings{},
      [&](const auto& block, Findings f) {
        for (std::size_t i = block.begin(); i != block.end(); ++i) {
          if (!found(i)) continue;
          ++f.count;
          f.first = std::min(f.first, i);
        }
        return f;
      },
      [](Findings a, const Findings& b) {
        return Findings{a.count + b.count, std::min(a.first, b.first)};
      });
}

// Finite and within +-limit (NaN fails both comparisons).
bool representable(double v, double limit) { return v >= -limit && v <= limit; }

// The first coordinate of point i (with displacement) outside the range, else its x: what the
// check tests and the message names.
double extreme_coordinate(const PointSource& points, std::size_t i) {
  return with_points(points, [&](const auto* xyz, const auto* disp) {
    double p[3];
    point_position(xyz, disp, i, p);
    for (double c : p) {
      if (!representable(c, kMaxCoordinate)) return c;
    }
    return p[0];
  });
}

double field_value(const FieldSource& field, std::size_t i) {
  return with_scalar(field.kind, [&](auto tag) {
    return static_cast<double>(static_cast<const decltype(tag)*>(field.values)[i]);
  });
}

bool good_point(const PointSource& points, std::size_t i) {
  return representable(extreme_coordinate(points, i), kMaxCoordinate);
}

bool good_value(const FieldSource& field, std::size_t i) {
  return representable(field_value(field, i), kMaxFieldValue);
}

// "non-finite coordinate nan at point 3 (1 such point); ..." or "coordinate 1e+308 at point 3
// (1 such point) is beyond the renderer's float range +-1e+12; ...".
std::string describe(const char* what, double value, double limit, const Findings& f) {
  std::ostringstream out;
  out << (std::isfinite(value) ? "" : "non-finite ") << what << ' ' << value << " at point "
      << f.first << " (" << f.count << " such point" << (f.count == 1 ? "" : "s") << ")";
  if (std::isfinite(value)) out << " is beyond the renderer's float range +-" << limit;
  out << "; policy is 'error'";
  return out.str();
}

}  // namespace

MeshCheck check_mesh(std::span<const std::int64_t> tets, const PointSource& points,
                     const FieldSource& field, NonFinitePolicy policy,
                     std::vector<std::uint8_t>& keep, bool check_indices) {
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
  const Findings out_of_range =
      check_indices
          ? find_all(tets.size(), [&](std::size_t i) { return tets[i] < 0 || tets[i] >= n; })
          : Findings{};
  check.tets_out_of_range = out_of_range.count;
  if (out_of_range.count) {
    const std::size_t i = out_of_range.first;
    check.error = "tet " + std::to_string(i / 4) + " has point index " + std::to_string(tets[i]) +
                  " outside [0, " + std::to_string(n) + ")";
    return check;
  }
  const Findings bad_points =
      find_all(points.count, [&](std::size_t i) { return !good_point(points, i); });
  const Findings bad_values =
      field.values ? find_all(field.count, [&](std::size_t i) { return !good_value(field, i); })
                   : Findings{};
  check.nonfinite_points = bad_points.count;
  check.nonfinite_values = bad_values.count;
  if (policy == NonFinitePolicy::error) {
    if (bad_points.count) {
      check.error = describe("coordinate", extreme_coordinate(points, bad_points.first),
                             kMaxCoordinate, bad_points);
    } else if (bad_values.count) {
      check.error =
          describe("field value", field_value(field, bad_values.first), kMaxFieldValue, bad_values);
    }
    return check;
  }
  if (!bad_points.count && !bad_values.count) return check;
  auto bad = [&](std::int64_t p) {
    if (p < 0 || p >= n) return true;
    const auto i = static_cast<std::size_t>(p);
    return !good_point(points, i) || (field.values && !good_value(field, i));
  };
  check.tets_skipped = find_all(tet_count, [&](std::size_t t) {
                         const std::int64_t* v = &tets[4 * t];
                         keep[t] = !(bad(v[0]) || bad(v[1]) || bad(v[2]) || bad(v[3]));
                         return !keep[t];
                       }).count;
  return check;
}

}  // namespace tetray::render
