// Distributed conjugate gradients with a Jacobi preconditioner for symmetric positive definite
// systems A x = b with prescribed (Dirichlet) dofs. The prescribed dofs are eliminated: they keep
// the values x holds on entry, and their rows are left out of the iteration.
#pragma once

#include <cstdint>
#include <span>

#include "minisolver/csr_matrix.hpp"
#include "minisolver/dof_space.hpp"

namespace minisolver {

struct CgSettings {
  double rtol = 1e-10;  // residual norm relative to the initial residual
  int max_iterations = 20000;
};

struct CgResult {
  bool converged = false;
  int iterations = 0;
  double relative_residual = 0;
};

// b: assembled (consistent) right-hand side; x: initial guess, prescribed values in fixed dofs.
CgResult solve_cg(const CsrMatrix& a, const DofSpace& space, std::span<const std::uint8_t> fixed,
                  std::span<const double> b, std::span<double> x, const CgSettings& settings);

// y = A x completed across ranks.
void apply(const CsrMatrix& a, const DofSpace& space, std::span<const double> x,
           std::span<double> y);

}  // namespace minisolver
