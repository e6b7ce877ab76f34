// Reading the solver's float or double arrays without a branch per element: the kernels are
// instantiated for each combination of element types once, at the start of a pass.
#pragma once

#include <type_traits>
#include <utility>

#include "render/volume/point_source.hpp"

namespace tetray::render {

// Calls f(type_tag) with a value of float or double matching `kind`.
template <typename F>
decltype(auto) with_scalar(ScalarKind kind, F&& f) {
  return kind == ScalarKind::f32 ? std::forward<F>(f)(float{}) : std::forward<F>(f)(double{});
}

// Calls f(const P* xyz, const D* displacement) with the arrays' real element types; a missing
// displacement comes as a null pointer of the same type as the coordinates.
template <typename F>
decltype(auto) with_points(const PointSource& points, F&& f) {
  return with_scalar(points.xyz_kind, [&](auto p) {
    using P = decltype(p);
    const auto* xyz = static_cast<const P*>(points.xyz);
    if (!points.displacement) return f(xyz, static_cast<const P*>(nullptr));
    return with_scalar(points.displacement_kind, [&](auto d) {
      using D = decltype(d);
      return f(xyz, static_cast<const D*>(points.displacement));
    });
  });
}

// Position of point i in double: coordinates plus displacement.
template <typename P, typename D>
inline void point_position(const P* xyz, const D* displacement, std::size_t i, double out[3]) {
  for (int a = 0; a < 3; ++a) {
    out[a] = static_cast<double>(xyz[3 * i + a]);
    if (displacement) out[a] += static_cast<double>(displacement[3 * i + a]);
  }
}

}  // namespace tetray::render
