#include "minisolver/heat.hpp"

#include "minisolver/assembly.hpp"
#include "minisolver/nodal.hpp"

namespace minisolver {
namespace {

double theta_of(ThetaScheme scheme) { return scheme == ThetaScheme::backward_euler ? 1.0 : 0.5; }

}  // namespace

HeatSolver::HeatSolver(const LocalMesh& mesh, const Comm& comm, HeatSetup setup, HeatData data,
                       double start_time)
    : mesh_(mesh),
      setup_(std::move(setup)),
      data_(std::move(data)),
      space_(mesh, comm, 1),
      mass_(make_pattern(mesh.tets, mesh.point_count(), 1)),
      unit_mass_(mass_.pattern),
      stiffness_(mass_.pattern),
      system_(mass_.pattern),
      fixed_(fixed_dofs(mesh, setup_.fixed_faces, 1)),
      time_(start_time) {
  const auto& m = setup_.materials;
  mass_ = assemble_mass(mesh, mass_.pattern, per_tet(mesh, m, [](auto& x) { return x.capacity; }));
  unit_mass_ = assemble_mass(mesh, mass_.pattern, std::vector<double>(mesh.tet_count(), 1.0));
  stiffness_ = assemble_diffusion(mesh, mass_.pattern,
                                  per_tet(mesh, m, [](auto& x) { return x.conductivity; }));
  system_ = mass_.plus(theta_of(setup_.scheme) * setup_.dt, stiffness_);
  u_ = interpolate(mesh, 1, [&](const Vec3& x, double* out) { *out = data_.prescribed(x, time_); });
  load_now_ = load(time_);
}

std::vector<double> HeatSolver::load(double t) const {
  const std::vector<double> f =
      interpolate(mesh_, 1, [&](const Vec3& x, double* out) { *out = data_.source(x, t); });
  std::vector<double> loaded(f.size());
  apply(unit_mass_, space_, f, loaded);
  return loaded;
}

StepOutcome HeatSolver::step() {
  const double theta = theta_of(setup_.scheme), dt = setup_.dt;
  const double next_time = time_ + dt;
  const std::vector<double> load_next = load(next_time);
  std::vector<double> mu(u_.size()), ku(u_.size()), rhs(u_.size());
  apply(mass_, space_, u_, mu);
  apply(stiffness_, space_, u_, ku);
  for (std::size_t i = 0; i < rhs.size(); ++i)
    rhs[i] =
        mu[i] - (1 - theta) * dt * ku[i] + dt * (theta * load_next[i] + (1 - theta) * load_now_[i]);
  for (std::size_t p = 0; p < u_.size(); ++p)
    if (fixed_[p]) u_[p] = data_.prescribed(mesh_.point(p), next_time);
  const CgResult cg = solve_cg(system_, space_, fixed_, rhs, u_, setup_.cg);
  if (!cg.converged)
    return {false,
            "heat: CG did not converge at t = " + std::to_string(next_time) + " (" +
                std::to_string(cg.iterations) + " iterations, relative residual " +
                std::to_string(cg.relative_residual) + ")",
            cg.iterations};
  time_ = next_time;
  load_now_ = load_next;
  return {true, {}, cg.iterations};
}

}  // namespace minisolver
