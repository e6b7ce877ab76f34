#include "minisolver/cg.hpp"

#include <cmath>
#include <vector>

namespace minisolver {

void apply(const CsrMatrix& a, const DofSpace& space, std::span<const double> x,
           std::span<double> y) {
  a.multiply(x, y);
  space.accumulate(y);
}

CgResult solve_cg(const CsrMatrix& a, const DofSpace& space, std::span<const std::uint8_t> fixed,
                  std::span<const double> b, std::span<double> x, const CgSettings& settings) {
  const std::size_t n = space.size();
  std::vector<double> r(n), z(n), p(n), q(n);
  std::vector<double> inverse_diagonal = a.diagonal();
  space.accumulate(inverse_diagonal);
  for (double& d : inverse_diagonal) d = d != 0 ? 1 / d : 0;

  apply(a, space, x, r);
  for (std::size_t i = 0; i < n; ++i) r[i] = fixed[i] ? 0 : b[i] - r[i];
  const double initial = std::sqrt(space.dot(r, r));
  CgResult result{true, 0, 0};
  if (initial == 0) return result;

  for (std::size_t i = 0; i < n; ++i) p[i] = z[i] = r[i] * inverse_diagonal[i];
  double rz = space.dot(r, z);
  for (int it = 1; it <= settings.max_iterations; ++it) {
    apply(a, space, p, q);
    for (std::size_t i = 0; i < n; ++i)
      if (fixed[i]) q[i] = 0;
    const double alpha = rz / space.dot(p, q);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] += alpha * p[i];
      r[i] -= alpha * q[i];
    }
    result.iterations = it;
    result.relative_residual = std::sqrt(space.dot(r, r)) / initial;
    if (!std::isfinite(result.relative_residual)) break;
    if (result.relative_residual <= settings.rtol) return result;
    for (std::size_t i = 0; i < n; ++i) z[i] = r[i] * inverse_diagonal[i];
    const double rz_next = space.dot(r, z);
    const double beta = rz_next / rz;
    rz = rz_next;
    for (std::size_t i = 0; i < n; ++i) p[i] = z[i] + beta * p[i];
  }
  result.converged = false;
  return result;
}

}  // namespace minisolver
