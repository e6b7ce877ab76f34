#include "run_report.hpp"

#include <algorithm>
#include <cstdio>

#include "minisolver/locking.hpp"

namespace minisolver {

void say(const Comm& comm, const std::string& line) {
  if (comm.rank() == 0) std::printf("%s\n", line.c_str());
}

void report_mesh(const SolverConfig& config, const LocalMesh& mesh, const Comm& comm) {
  const auto tets = static_cast<long long>(comm.sum(static_cast<double>(mesh.tet_count())));
  if (comm.rank() == 0) std::printf("mesh: %lld tets over %d ranks\n", tets, comm.size());
  if (!config.stiff_region) return;
  const StiffRegion& region = *config.stiff_region;
  const auto stiff = static_cast<long long>(
      comm.sum(static_cast<double>(std::count(mesh.material.begin(), mesh.material.end(), 1))));
  if (comm.rank() == 0)
    std::printf("stiff region %c > %g: %lld of %lld tets, stiffness times %g\n",
                static_cast<char>('x' + region.axis), region.above, stiff, tets, region.contrast);
}

void report_locking(const ElasticSetup& setup, const Comm& comm) {
  double poisson = 0;
  for (const ElasticMaterial& m : setup.materials) poisson = std::max(poisson, m.poisson);
  if (poisson <= locking_poisson) return;
  const LockingMeasurement locking = measure_locking(poisson, comm);
  if (comm.rank() != 0) return;
  std::printf(
      "elasticity: Poisson ratio %g > %g, P1 locking expected (linear tets resist volume change "
      "too much, displacements come out too small); ",
      poisson, locking_poisson);
  if (locking.ok)
    std::printf(
        "measured on a manufactured solution: L2 error %.3g times that at Poisson ratio %g\n",
        locking.ratio, locking_reference_poisson);
  else
    std::printf("its measurement failed: %s\n", locking.message.c_str());
}

void report_time_step(const ElasticSolver& solver, const ElasticSetup& setup, const Comm& comm) {
  const double limit = solver.cfl_limit().dt;
  if (comm.rank() == 0)
    std::printf(
        "elasticity: %s, dt = %g, central-difference CFL limit dt_max = %.4g (dt / dt_max = "
        "%.3g)\n",
        setup.scheme == ElasticScheme::newmark ? "newmark (implicit, unconditionally stable)"
                                               : "central differences (explicit)",
        setup.dt, limit, setup.dt / limit);
}

void report_blocked(const Comm& comm, double wall_seconds, double blocked_seconds) {
  if (comm.rank() != 0) return;
  const double percent = wall_seconds > 0 ? 100 * blocked_seconds / wall_seconds : 0;
  std::printf("tetray-minisolver: wall %.3f s, blocked in tetray %.3f s (%.0f%%)\n", wall_seconds,
              blocked_seconds, percent);
}

}  // namespace minisolver
