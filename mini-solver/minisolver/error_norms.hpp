// Discretization errors against an exact field: the L2 norm of (u_h - u) over the mesh, with a
// degree-2 quadrature rule per tet, and the largest nodal error.
#pragma once

#include <functional>
#include <span>

#include "minisolver/dof_space.hpp"

namespace minisolver {

struct ErrorNorms {
  double l2 = 0;
  double max = 0;
};

// exact(x, out) writes the space.components() values of the exact field at x.
ErrorNorms error_norms(const DofSpace& space, std::span<const double> uh,
                       const std::function<void(const Vec3&, double*)>& exact);

}  // namespace minisolver
