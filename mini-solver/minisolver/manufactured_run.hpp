// One manufactured-solution run from start to end time on a distributed mesh: the error at the
// end against the exact field and the wall time it took (the slowest rank), the unit of the
// study mode and of the convergence tests.
#pragma once

#include <string>

#include "minisolver/elasticity.hpp"
#include "minisolver/error_norms.hpp"
#include "minisolver/heat.hpp"
#include "minisolver/manufactured.hpp"

namespace minisolver {

struct RunResult {
  bool ok = true;
  std::string message;
  ErrorNorms error;
  double seconds = 0;
  int steps = 0;
};

// Unit conductivity and capacity; every face of the cube held at the exact temperature.
RunResult run_manufactured_heat(const LocalMesh& mesh, const Comm& comm, ThetaScheme scheme,
                                double dt, double end_time, const Separable& field,
                                const CgSettings& cg = {});

// One material; every face held at the exact displacement.
RunResult run_manufactured_elastic(const LocalMesh& mesh, const Comm& comm, ElasticScheme scheme,
                                   double dt, double end_time, const ElasticData& data,
                                   const ElasticMaterial& material, const CgSettings& cg = {});

// Number of steps of at most `dt` that reach `end_time` exactly.
int steps_to_reach(double end_time, double dt);

}  // namespace minisolver
