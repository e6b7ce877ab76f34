#include "minisolver/manufactured_run.hpp"

#include <chrono>
#include <cmath>

namespace minisolver {
namespace {

double seconds_since(std::chrono::steady_clock::time_point start, const Comm& comm) {
  const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
  return comm.max(elapsed.count());
}

// Advances `solver` the given number of steps; the first failure ends the run.
template <class Solver>
RunResult advance(Solver& solver, int steps) {
  RunResult result;
  for (int s = 0; s < steps; ++s) {
    const StepOutcome outcome = solver.step();
    if (!outcome.ok) return {false, outcome.message, {}, 0, s};
  }
  result.steps = steps;
  return result;
}

}  // namespace

int steps_to_reach(double end_time, double dt) {
  return static_cast<int>(std::ceil(end_time / dt - 1e-9));
}

RunResult run_manufactured_heat(const LocalMesh& mesh, const Comm& comm, ThetaScheme scheme,
                                double dt, double end_time, const Separable& field,
                                const CgSettings& cg) {
  const auto start = std::chrono::steady_clock::now();
  const int steps = steps_to_reach(end_time, dt);
  HeatSetup setup;
  setup.scheme = scheme;
  setup.dt = end_time / steps;
  setup.fixed_faces = all_faces;
  setup.cg = cg;
  HeatSolver solver(mesh, comm, setup, manufactured_heat(field));
  RunResult result = advance(solver, steps);
  result.seconds = seconds_since(start, comm);
  if (!result.ok) return result;
  result.error = error_norms(solver.space(), solver.temperature(), [&](const Vec3& x, double* out) {
    *out = field.value(x) * field.profile_derivative(solver.time(), 0);
  });
  return result;
}

RunResult run_manufactured_elastic(const LocalMesh& mesh, const Comm& comm, ElasticScheme scheme,
                                   double dt, double end_time, const ElasticData& data,
                                   const ElasticMaterial& material, const CgSettings& cg) {
  const auto start = std::chrono::steady_clock::now();
  const int steps = steps_to_reach(end_time, dt);
  ElasticSetup setup;
  setup.materials = {material};
  setup.scheme = scheme;
  setup.dt = end_time / steps;
  setup.fixed_faces = all_faces;
  setup.cg = cg;
  std::string error;
  const auto solver = ElasticSolver::create(mesh, comm, setup, data, error);
  if (!solver) return {false, error, {}, seconds_since(start, comm), 0};
  RunResult result = advance(*solver, steps);
  result.seconds = seconds_since(start, comm);
  if (!result.ok) return result;
  result.error =
      error_norms(solver->space(), solver->displacement(), [&](const Vec3& x, double* out) {
        const Vec3 u = data.prescribed(x, solver->time()).displacement;
        std::copy(u.begin(), u.end(), out);
      });
  return result;
}

}  // namespace minisolver
