#include "minisolver/elasticity.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "minisolver/nodal.hpp"

namespace minisolver {
namespace {

double largest_face_area(const std::array<Vec3, 4>& x) {
  static constexpr int kFaces[4][3] = {{1, 2, 3}, {0, 2, 3}, {0, 1, 3}, {0, 1, 2}};
  double largest = 0;
  for (const auto& f : kFaces) {
    Vec3 e1{}, e2{};
    for (int a = 0; a < 3; ++a) {
      e1[a] = x[f[1]][a] - x[f[0]][a];
      e2[a] = x[f[2]][a] - x[f[0]][a];
    }
    const Vec3 n{e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                 e1[0] * e2[1] - e1[1] * e2[0]};
    largest = std::max(largest, 0.5 * std::sqrt(dot(n, n)));
  }
  return largest;
}

double gershgorin_bound(const ElasticBlock& k) {
  double bound = 0;
  for (int r = 0; r < 12; ++r) {
    double row = 0;
    for (int c = 0; c < 12; ++c) row += std::abs(k[r * 12 + c]);
    bound = std::max(bound, row);
  }
  return bound;
}

std::string format(double value) {
  std::ostringstream s;
  s.precision(4);
  s << value;
  return s.str();
}

}  // namespace

Lame ElasticMaterial::lame() const {
  return {young * poisson / ((1 + poisson) * (1 - 2 * poisson)), young / (2 * (1 + poisson))};
}

double ElasticMaterial::wave_speed() const {
  const Lame l = lame();
  return std::sqrt((l.lambda + 2 * l.mu) / density);
}

CflLimit central_difference_limit(const LocalMesh& mesh, const Comm& comm,
                                  const std::vector<ElasticMaterial>& materials) {
  double omega_squared = 0, smallest_height = HUGE_VAL, speed = 0;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const ElasticMaterial& m = materials.at(mesh.material[t]);
    const auto x = mesh.tet_points(t);
    const TetGeometry g = tet_geometry(x);
    const double lumped = m.density * g.volume / 4;
    omega_squared =
        std::max(omega_squared, gershgorin_bound(elastic_element_matrix(g, m.lame())) / lumped);
    smallest_height = std::min(smallest_height, 3 * g.volume / largest_face_area(x));
    speed = std::max(speed, m.wave_speed());
  }
  omega_squared = comm.max(omega_squared);
  return {omega_squared > 0 ? 2 / std::sqrt(omega_squared) : HUGE_VAL, -comm.max(-smallest_height),
          comm.max(speed)};
}

std::unique_ptr<ElasticSolver> ElasticSolver::create(const LocalMesh& mesh, const Comm& comm,
                                                     ElasticSetup setup, ElasticData data,
                                                     std::string& error, double start_time) {
  if (setup.scheme == ElasticScheme::central_difference) {
    const CflLimit cfl = central_difference_limit(mesh, comm, setup.materials);
    if (setup.dt > cfl.dt && !setup.allow_unstable) {
      error = "elasticity: central differences with dt = " + format(setup.dt) +
              " exceed the CFL limit dt_max = " + format(cfl.dt) + " (smallest tet height " +
              format(cfl.smallest_height) + ", wave speed " + format(cfl.wave_speed) +
              "); lower dt below the limit or use scheme newmark";
      return nullptr;
    }
  }
  auto solver =
      std::make_unique<ElasticSolver>(mesh, comm, std::move(setup), std::move(data), start_time);
  const StepOutcome start = solver->solve_initial_acceleration();
  if (!start.ok) {
    error = start.message;
    return nullptr;
  }
  return solver;
}

ElasticSolver::ElasticSolver(const LocalMesh& mesh, const Comm& comm, ElasticSetup setup,
                             ElasticData data, double start_time)
    : mesh_(mesh),
      setup_(std::move(setup)),
      data_(std::move(data)),
      space_(mesh, comm, 3),
      stiffness_(make_pattern(mesh.tets, mesh.point_count(), 3)),
      fixed_(fixed_dofs(mesh, setup_.fixed_faces, 3)),
      time_(start_time),
      cfl_(central_difference_limit(mesh, comm, setup_.materials)) {
  const auto& m = setup_.materials;
  std::vector<Lame> lame(mesh.tet_count());
  for (std::size_t t = 0; t < lame.size(); ++t) lame[t] = m.at(mesh.material[t]).lame();
  stiffness_ = assemble_elasticity(mesh, stiffness_.pattern, lame);
  const std::vector<double> density = per_tet(mesh, m, [](auto& x) { return x.density; });
  if (setup_.scheme == ElasticScheme::newmark) {
    unit_mass_ =
        assemble_mass(mesh, stiffness_.pattern, std::vector<double>(mesh.tet_count(), 1.0));
    mass_ = assemble_mass(mesh, stiffness_.pattern, density);
    newmark_system_ = stiffness_.plus(4 / (setup_.dt * setup_.dt), *mass_);
  } else {
    lumped_ = lumped_mass(mesh, 3, density);
    space_.accumulate(lumped_);
    unit_lumped_ = lumped_mass(mesh, 3, std::vector<double>(mesh.tet_count(), 1.0));
    space_.accumulate(unit_lumped_);
  }
  u_.assign(space_.size(), 0.0);
  v_ = a_ = u_;
  prescribe(u_, 0, time_);
  prescribe(v_, 1, time_);
}

// Writes the prescribed displacement (0), velocity (1) or acceleration (2) at time t at every dof;
// callers keep what they need (the fixed dofs, or everything at the start).
void ElasticSolver::prescribe(std::span<double> values, int derivative, double t) const {
  for (std::size_t p = 0; p < mesh_.point_count(); ++p) {
    const Kinematics k = data_.prescribed(mesh_.point(p), t);
    const Vec3& v =
        derivative == 0 ? k.displacement : (derivative == 1 ? k.velocity : k.acceleration);
    for (int i = 0; i < 3; ++i) values[3 * p + i] = v[i];
  }
}

std::vector<double> ElasticSolver::load(double t) const {
  const std::vector<double> f = interpolate(mesh_, 3, [&](const Vec3& x, double* out) {
    const Vec3 b = data_.body_force(x, t);
    std::copy(b.begin(), b.end(), out);
  });
  std::vector<double> loaded(f.size());
  if (setup_.scheme == ElasticScheme::newmark) {
    apply(*unit_mass_, space_, f, loaded);
  } else {
    for (std::size_t i = 0; i < f.size(); ++i) loaded[i] = unit_lumped_[i] * f[i];
  }
  return loaded;
}

StepOutcome ElasticSolver::solve_initial_acceleration() {
  const std::vector<double> force = load(time_);
  std::vector<double> ku(u_.size());
  apply(stiffness_, space_, u_, ku);
  prescribe(a_, 2, time_);
  std::vector<double> rhs(u_.size());
  for (std::size_t i = 0; i < rhs.size(); ++i) rhs[i] = force[i] - ku[i];
  if (setup_.scheme == ElasticScheme::central_difference) {
    for (std::size_t i = 0; i < rhs.size(); ++i)
      if (!fixed_[i]) a_[i] = rhs[i] / lumped_[i];
    const double dt = setup_.dt;
    u_previous_.resize(u_.size());
    for (std::size_t i = 0; i < u_.size(); ++i)
      u_previous_[i] = u_[i] - dt * v_[i] + 0.5 * dt * dt * a_[i];
    std::vector<double> mv(u_.size());
    for (std::size_t i = 0; i < mv.size(); ++i) mv[i] = lumped_[i] * v_[i];
    initial_energy_ = last_energy_ = 0.5 * (space_.dot(v_, mv) + space_.dot(u_, ku));
    return {};
  }
  const CgResult cg = solve_cg(*mass_, space_, fixed_, rhs, a_, setup_.cg);
  if (!cg.converged)
    return {false, "elasticity: the initial acceleration did not converge", cg.iterations};
  initial_energy_ = energy();
  return {true, {}, cg.iterations};
}

double ElasticSolver::energy() const {
  if (setup_.scheme == ElasticScheme::central_difference) return last_energy_;
  std::vector<double> mv(u_.size()), ku(u_.size());
  apply(*mass_, space_, v_, mv);
  apply(stiffness_, space_, u_, ku);
  return 0.5 * (space_.dot(v_, mv) + space_.dot(u_, ku));
}

StepOutcome ElasticSolver::step() {
  return setup_.scheme == ElasticScheme::newmark ? step_newmark() : step_central_difference();
}

StepOutcome ElasticSolver::step_central_difference() {
  const double dt = setup_.dt, next_time = time_ + dt;
  const std::vector<double> force = load(time_);
  std::vector<double> ku(u_.size()), next(u_.size());
  apply(stiffness_, space_, u_, ku);
  for (std::size_t i = 0; i < u_.size(); ++i)
    next[i] = 2 * u_[i] - u_previous_[i] + dt * dt * (force[i] - ku[i]) / lumped_[i];
  std::vector<double> prescribed(u_.size());
  prescribe(prescribed, 0, next_time);
  for (std::size_t i = 0; i < u_.size(); ++i)
    if (fixed_[i]) next[i] = prescribed[i];

  // Work of all forces (loads and reactions) over the step, and the energy at the current time.
  std::vector<double> total_force(u_.size()), stroke(u_.size()), mv(u_.size());
  for (std::size_t i = 0; i < u_.size(); ++i) {
    total_force[i] = lumped_[i] * (next[i] - 2 * u_[i] + u_previous_[i]) / (dt * dt) + ku[i];
    stroke[i] = 0.5 * (next[i] - u_previous_[i]);
    v_[i] = stroke[i] / dt;
    mv[i] = lumped_[i] * v_[i];
  }
  supplied_work_ += std::abs(space_.dot(total_force, stroke));
  const StepOutcome watched = check_energy(0.5 * (space_.dot(v_, mv) + space_.dot(u_, ku)));
  if (!watched.ok) return watched;
  u_previous_.swap(u_);
  u_.swap(next);
  time_ = next_time;
  return {};
}

StepOutcome ElasticSolver::check_energy(double energy_now) {
  last_energy_ = energy_now;
  const double allowed = setup_.energy_growth_limit * (initial_energy_ + supplied_work_);
  if (std::isfinite(energy_now) && energy_now <= allowed) return {};
  return {false,
          "elasticity: central differences unstable at t = " + format(time_) + ": energy " +
              format(energy_now) + " exceeds " + format(setup_.energy_growth_limit) +
              " times the energy supplied (" + format(initial_energy_ + supplied_work_) +
              "); dt = " + format(setup_.dt) +
              " is above the CFL limit dt_max = " + format(cfl_.dt) + "; run stopped",
          0};
}

StepOutcome ElasticSolver::step_newmark() {
  const double dt = setup_.dt, next_time = time_ + dt;
  const double c0 = 4 / (dt * dt), c1 = 4 / dt;
  const std::vector<double> force = load(next_time);
  std::vector<double> g(u_.size()), g_velocity(u_.size()), g_acceleration(u_.size());
  prescribe(g, 0, next_time);
  prescribe(g_velocity, 1, next_time);
  prescribe(g_acceleration, 2, next_time);
  // The system's mass term implies a_next = c0 u_next - history; on fixed dofs the history is
  // chosen so that this is the prescribed acceleration, which keeps the scheme second order
  // under moving boundaries.
  std::vector<double> history(u_.size()), rhs(u_.size()), next(u_.size());
  for (std::size_t i = 0; i < u_.size(); ++i) {
    history[i] = fixed_[i] ? c0 * g[i] - g_acceleration[i] : c0 * u_[i] + c1 * v_[i] + a_[i];
    next[i] = fixed_[i] ? g[i] : u_[i] + dt * v_[i] + 0.25 * dt * dt * a_[i];
  }
  apply(*mass_, space_, history, rhs);
  for (std::size_t i = 0; i < u_.size(); ++i) rhs[i] += force[i];
  const CgResult cg = solve_cg(*newmark_system_, space_, fixed_, rhs, next, setup_.cg);
  if (!cg.converged)
    return {false, "elasticity: Newmark CG did not converge at t = " + format(next_time),
            cg.iterations};
  for (std::size_t i = 0; i < u_.size(); ++i) {
    const double a_next =
        fixed_[i] ? g_acceleration[i] : c0 * (next[i] - u_[i]) - c1 * v_[i] - a_[i];
    v_[i] = fixed_[i] ? g_velocity[i] : v_[i] + 0.5 * dt * (a_[i] + a_next);
    a_[i] = a_next;
  }
  u_.swap(next);
  time_ = next_time;
  return {true, {}, cg.iterations};
}

}  // namespace minisolver
