// Volumetric locking of P1 tets, measured rather than assumed: as the Poisson ratio nears 1/2,
// linear tets cannot change shape without changing volume, and the discrete solution comes out
// too stiff. The run and the tests report the same figure.
#pragma once

#include <string>

#include "minisolver/comm.hpp"

namespace minisolver {

struct LockingMeasurement {
  bool ok = true;
  std::string message;
  double error = 0;            // L2 error at the Poisson ratio asked for
  double reference_error = 0;  // the same at the reference ratio 0.3
  double ratio = 0;            // error / reference_error: near 1 without locking
};

inline constexpr double locking_reference_poisson = 0.3;

// A divergence-free manufactured displacement (its body force does not depend on lambda, so the
// exact solution is the same for every Poisson ratio) on the unit cube of cells^3 hexahedra,
// distributed over `comm`, shear modulus 1, two Newmark steps: its L2 error at `poisson` against
// that at the reference ratio. Collective.
LockingMeasurement measure_locking(double poisson, const Comm& comm, int cells = 6);

}  // namespace minisolver
