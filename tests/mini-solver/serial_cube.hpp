// The unit cube meshed as n^3 Kuhn hexahedra on one process, the setting of most solver tests.
#pragma once

#include <cmath>
#include <vector>

#include "minisolver/local_mesh.hpp"

namespace minisolver::testing {

struct SerialMesh {
  SerialComm comm;
  Mesh mesh;
  LocalMesh local;

  explicit SerialMesh(Mesh m) : mesh(std::move(m)), local(distribute(mesh, comm)) {}
};

inline Mesh unit_cube(int n) { return make_beam({n, n, n}, {0, 0, 0}, {1, 1, 1}); }

// Observed order of convergence between successive entries of a ladder refined by `ratio`.
inline std::vector<double> observed_orders(const std::vector<double>& errors, double ratio = 2) {
  std::vector<double> orders;
  for (std::size_t i = 1; i < errors.size(); ++i)
    orders.push_back(std::log(errors[i - 1] / errors[i]) / std::log(ratio));
  return orders;
}

}  // namespace minisolver::testing
