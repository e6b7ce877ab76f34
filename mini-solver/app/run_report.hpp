// What a run tells its user (on rank 0) about its setup before stepping: the mesh and the stiff
// region, P1 locking when the Poisson ratio makes it expected (measured, not only warned of), and
// the elastic time step against the explicit stability limit; and at its end, the share of its
// wall time that tetray took.
#pragma once

#include <chrono>
#include <string>

#include "minisolver/local_mesh.hpp"
#include "minisolver/solver_config.hpp"

namespace minisolver {

// Prints on rank 0 only.
void say(const Comm& comm, const std::string& line);

// Tet counts, and those of the stiff region. Collective.
void report_mesh(const SolverConfig& config, const LocalMesh& mesh, const Comm& comm);

// Above this Poisson ratio (lambda = 9 mu) P1 locking is noticeable; the run says so and measures
// it. Collective.
inline constexpr double locking_poisson = 0.45;
void report_locking(const ElasticSetup& setup, const Comm& comm);

// dt against the central-difference CFL limit, whichever scheme runs.
void report_time_step(const ElasticSolver& solver, const ElasticSetup& setup, const Comm& comm);

// Seconds on the steady clock since construction.
class Seconds {
 public:
  double elapsed() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// The run's wall time beside the time tetray blocked it, and their ratio, in one line on rank 0:
// "tetray-minisolver: wall 14.213 s, blocked in tetray 11.642 s (82%)".
void report_blocked(const Comm& comm, double wall_seconds, double blocked_seconds);

}  // namespace minisolver
