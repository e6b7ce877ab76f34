// Heat conduction c du/dt - div(k grad u) = f with P1 tets, advanced by the theta method
// (backward Euler theta = 1, Crank-Nicolson theta = 1/2); each step is one distributed CG solve
// of (M + theta dt K) u_next = (M - (1 - theta) dt K) u + dt (theta F_next + (1 - theta) F).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "minisolver/cg.hpp"
#include "minisolver/dof_space.hpp"
#include "minisolver/problem_data.hpp"

namespace minisolver {

struct HeatMaterial {
  double conductivity = 1;
  double capacity = 1;  // density times specific heat
};

enum class ThetaScheme { backward_euler, crank_nicolson };

struct HeatSetup {
  std::vector<HeatMaterial> materials{HeatMaterial{}};  // indexed by tet material
  ThetaScheme scheme = ThetaScheme::crank_nicolson;
  double dt = 0.01;
  std::uint8_t fixed_faces = 0;  // Face bits with prescribed temperature
  CgSettings cg;
};

class HeatSolver {
 public:
  HeatSolver(const LocalMesh& mesh, const Comm& comm, HeatSetup setup, HeatData data,
             double start_time = 0);

  StepOutcome step();
  std::span<const double> temperature() const { return u_; }
  double time() const { return time_; }
  const DofSpace& space() const { return space_; }

 private:
  std::vector<double> load(double t) const;  // assembled M1 f(t)

  const LocalMesh& mesh_;
  HeatSetup setup_;
  HeatData data_;
  DofSpace space_;
  CsrMatrix mass_;       // capacity-weighted
  CsrMatrix unit_mass_;  // for the source load
  CsrMatrix stiffness_;
  CsrMatrix system_;  // M + theta dt K
  std::vector<std::uint8_t> fixed_;
  std::vector<double> u_;
  std::vector<double> load_now_;
  double time_;
};

}  // namespace minisolver
