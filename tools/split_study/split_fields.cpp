#include "tools/split_study/split_fields.hpp"

#include <algorithm>
#include <cmath>

namespace tetray::tools {
namespace {

// The 1D Lagrange basis of `order` on the cell's nodes at t = 0, 1/order, ..., 1.
std::array<double, 3> basis(int order, double t) {
  if (order == 1) return {1 - t, t, 0};
  return {2 * (t - 0.5) * (t - 1), -4 * t * (t - 1), 2 * t * (t - 0.5)};
}

}  // namespace

double HexField::operator()(const Point3& x) const {
  const double h = 2.0 / cells;
  std::array<int, 3> cell{};
  std::array<std::array<double, 3>, 3> weights{};
  for (int a = 0; a < 3; ++a) {
    cell[a] = std::clamp(static_cast<int>(std::floor((x[a] + 1) / h)), 0, cells - 1);
    weights[a] = basis(order, (x[a] + 1) / h - cell[a]);
  }
  double value = 0;
  for (int i = 0; i <= order; ++i)
    for (int j = 0; j <= order; ++j)
      for (int k = 0; k <= order; ++k) {
        const Point3 node = {-1 + h * (cell[0] + double(i) / order),
                             -1 + h * (cell[1] + double(j) / order),
                             -1 + h * (cell[2] + double(k) / order)};
        value += weights[0][i] * weights[1][j] * weights[2][k] * g(node);
      }
  return value;
}

}  // namespace tetray::tools
