// Linear elastodynamics rho u'' - div sigma(u) = f with P1 tets, two time integrators:
// - central differences with lumped mass (explicit; stable only below the CFL limit, which is
//   computed from the element matrices; a larger dt is refused unless forced, and then the
//   energy is watched and the run stopped when it grows past what the loads supplied);
// - Newmark average acceleration (beta 1/4, gamma 1/2) with consistent mass (implicit,
//   unconditionally stable, conserves energy exactly without loads).
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "minisolver/assembly.hpp"
#include "minisolver/cg.hpp"
#include "minisolver/problem_data.hpp"

namespace minisolver {

struct ElasticMaterial {
  double young = 1;
  double poisson = 0.3;
  double density = 1;

  Lame lame() const;
  double wave_speed() const;  // pressure waves, the fastest
};

// The CFL limit 2 / omega_max, with omega_max^2 bounded above by the largest Gershgorin bound of
// the element matrices M_lumped^-1 K_e (an element eigenvalue bound, so the limit is safe), and
// the two figures it stands for: the smallest tet height and the fastest wave speed.
struct CflLimit {
  double dt = 0;
  double smallest_height = 0;
  double wave_speed = 0;
};
CflLimit central_difference_limit(const LocalMesh& mesh, const Comm& comm,
                                  const std::vector<ElasticMaterial>& materials);

enum class ElasticScheme { central_difference, newmark };

struct ElasticSetup {
  std::vector<ElasticMaterial> materials{ElasticMaterial{}};
  ElasticScheme scheme = ElasticScheme::newmark;
  double dt = 0.01;
  std::uint8_t fixed_faces = 0;  // Face bits with prescribed displacement (all components)
  CgSettings cg;
  bool allow_unstable = false;  // central differences above the CFL limit, watched by energy
  double energy_growth_limit = 100;
};

class ElasticSolver {
 public:
  // Null, with `error` set, when central differences are asked for above the CFL limit (unless
  // allow_unstable) or when the initial acceleration cannot be solved for.
  static std::unique_ptr<ElasticSolver> create(const LocalMesh& mesh, const Comm& comm,
                                               ElasticSetup setup, ElasticData data,
                                               std::string& error, double start_time = 0);

  StepOutcome step();
  std::span<const double> displacement() const { return u_; }
  std::span<const double> velocity() const { return v_; }
  double time() const { return time_; }
  // Kinetic plus strain energy, 1/2 v.M v + 1/2 u.K u, with the scheme's mass. Central
  // differences know the velocity one step late, so theirs is the energy of the previous step.
  double energy() const;
  // The largest stable central-difference step for this mesh and materials.
  const CflLimit& cfl_limit() const { return cfl_; }
  const DofSpace& space() const { return space_; }

  ElasticSolver(const LocalMesh& mesh, const Comm& comm, ElasticSetup setup, ElasticData data,
                double start_time);

 private:
  std::vector<double> load(double t) const;
  void prescribe(std::span<double> values, int derivative, double t) const;
  StepOutcome step_central_difference();
  StepOutcome step_newmark();
  StepOutcome check_energy(double energy_now);
  StepOutcome solve_initial_acceleration();

  const LocalMesh& mesh_;
  ElasticSetup setup_;
  ElasticData data_;
  DofSpace space_;
  CsrMatrix stiffness_;
  std::optional<CsrMatrix> unit_mass_;       // for the load (Newmark)
  std::optional<CsrMatrix> mass_;            // consistent, density-weighted (Newmark)
  std::optional<CsrMatrix> newmark_system_;  // K + 4/dt^2 M
  std::vector<double> lumped_;               // assembled lumped mass (central differences)
  std::vector<double> unit_lumped_;          // the same for unit density, for the load
  std::vector<std::uint8_t> fixed_;
  std::vector<double> u_, v_, a_, u_previous_;
  double time_;
  CflLimit cfl_;
  double initial_energy_ = 0;
  double last_energy_ = 0;
  double supplied_work_ = 0;  // sum of |work| done on the body, for the stability watch
};

}  // namespace minisolver
