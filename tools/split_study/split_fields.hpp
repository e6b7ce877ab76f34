// The finite-element fields of the split study: a smooth function g sampled at the nodes of a
// lattice of hexahedra on [-1, 1]^3 and interpolated in each cell, trilinearly (Q1, the field a
// solver's 8-node hexahedra carry) or triquadratically (Q2, its 27-node hexahedra).
#pragma once

#include <array>
#include <functional>
#include <string>

namespace tetray::tools {

using Point3 = std::array<double, 3>;

struct HexField {
  std::string name;  // "Q1 hexahedra" or "Q2 hexahedra"
  int order = 1;     // 1 or 2
  int cells = 4;     // per side
  std::function<double(const Point3&)> g;

  // The interpolant at x in [-1, 1]^3: g at the nodes of x's cell, weighted by the cell's
  // tensor-product Lagrange basis of `order`.
  double operator()(const Point3& x) const;
};

}  // namespace tetray::tools
