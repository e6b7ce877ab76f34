// Value ranges and bounding boxes in double precision that ignore non-finite values and values
// beyond the renderer's float range: the local
// parts of the global quantities (global_reduce.hpp) and the bounds that place the vertex
// store's origin.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "render/core/vec.hpp"

namespace tetray::render {

// What the renderer's float vertex store (render/volume/tet_volume.hpp) can hold: the tracer
// multiplies up to three coordinate differences in float (edge tests, plane distances), so
// |coordinate| <= 1e12 keeps every product below float's 3.4e38; field values are only
// interpolated and differenced, so |value| <= 1e30 leaves them eight orders of headroom. The
// mesh check refuses (or skips) what lies beyond, and the ranges below ignore it.
inline constexpr double kMaxCoordinate = 1e12;
inline constexpr double kMaxFieldValue = 1e30;

struct ValueRange {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();

  bool empty() const { return !(lo <= hi); }
  // Non-finite values and those beyond kMaxFieldValue are ignored: they have no place on a
  // colormap or in a camera fit.
  void include(double value) {
    if (!(std::abs(value) <= kMaxFieldValue)) return;
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
};

struct BoundingBox {
  ValueRange axis[3];

  bool empty() const { return axis[0].empty() || axis[1].empty() || axis[2].empty(); }
  // A point with a coordinate beyond kMaxCoordinate (or NaN) is ignored as a whole.
  void include(Vec3d point) {
    for (int a = 0; a < 3; ++a) {
      if (!(std::abs(point[a]) <= kMaxCoordinate)) return;
    }
    for (int a = 0; a < 3; ++a) axis[a].include(point[a]);
  }
  void merge(const BoundingBox& other) {
    for (int a = 0; a < 3; ++a) {
      axis[a].include(other.axis[a].lo);
      axis[a].include(other.axis[a].hi);
    }
  }
  Vec3d lo() const { return {axis[0].lo, axis[1].lo, axis[2].lo}; }
  Vec3d hi() const { return {axis[0].hi, axis[1].hi, axis[2].hi}; }
};

// The range of `values` on this rank (float or double arrays of the solver).
template <typename T>
ValueRange local_range(std::span<const T> values) {
  ValueRange range;
  for (T value : values) range.include(static_cast<double>(value));
  return range;
}

// The bounding box of interleaved xyz coordinates on this rank.
template <typename T>
BoundingBox local_bounds(std::span<const T> xyz) {
  BoundingBox box;
  for (std::size_t k = 0; k + 2 < xyz.size(); k += 3) {
    box.include({static_cast<double>(xyz[k]), static_cast<double>(xyz[k + 1]),
                 static_cast<double>(xyz[k + 2])});
  }
  return box;
}

}  // namespace tetray::render
