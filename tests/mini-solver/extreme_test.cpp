// Stiff and extreme cases: explicit steps above the CFL limit, a stiffness contrast of 1e6,
// nearly incompressible material (P1 locking, measured and reported), needle and plate meshes
// with aspect ratio 1000, and a rank with no tets.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "minisolver/locking.hpp"
#include "minisolver/manufactured_run.hpp"
#include "minisolver/partition.hpp"
#include "serial_cube.hpp"

namespace minisolver {
namespace {

using testing::SerialMesh;
using testing::unit_cube;

const CgSettings kTight{1e-12, 50000};

// Free vibration from a sine-shaped displacement, clamped on every face, no loads.
ElasticData free_vibration() {
  const Separable shape{Shape::sine, Profile::linear};
  return {[shape](const Vec3& x, double) {
            const double s = shape.value(x);
            return Kinematics{{s, 0.5 * s, -0.25 * s}, {}, {}};
          },
          [](const Vec3&, double) { return Vec3{}; }};
}

ElasticSetup clamped(ElasticScheme scheme, double dt, std::vector<ElasticMaterial> materials) {
  ElasticSetup setup;
  setup.materials = std::move(materials);
  setup.scheme = scheme;
  setup.dt = dt;
  setup.fixed_faces = all_faces;
  setup.cg = kTight;
  return setup;
}

bool all_finite(std::span<const double> values) {
  return std::all_of(values.begin(), values.end(), [](double v) { return std::isfinite(v); });
}

double max_abs(std::span<const double> values) {
  double largest = 0;
  for (const double v : values) largest = std::max(largest, std::abs(v));
  return largest;
}

double max_difference(std::span<const double> a, std::span<const double> b) {
  double largest = 0;
  for (std::size_t k = 0; k < a.size(); ++k) largest = std::max(largest, std::abs(a[k] - b[k]));
  return largest;
}

std::string formatted(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

TEST(Extreme, CentralDifferencesAboveCflAreRefusedNamingTheLimit) {
  const SerialMesh m(unit_cube(3));
  const double limit = central_difference_limit(m.local, m.comm, {ElasticMaterial{}}).dt;
  std::string error;
  const auto solver = ElasticSolver::create(
      m.local, m.comm, clamped(ElasticScheme::central_difference, 2 * limit, {ElasticMaterial{}}),
      free_vibration(), error);
  EXPECT_EQ(solver, nullptr);
  EXPECT_NE(error.find("CFL limit dt_max = " + formatted(limit)), std::string::npos) << error;
}

TEST(Extreme, ForcedUnstableCentralDifferencesStopCleanly) {
  const SerialMesh m(unit_cube(3));
  ElasticSetup setup = clamped(ElasticScheme::central_difference, 1.0, {ElasticMaterial{}});
  setup.dt = 3 * central_difference_limit(m.local, m.comm, setup.materials).dt;
  setup.allow_unstable = true;
  std::string error;
  const auto solver = ElasticSolver::create(m.local, m.comm, setup, free_vibration(), error);
  ASSERT_NE(solver, nullptr) << error;
  StepOutcome outcome;
  for (int s = 0; s < 2000 && outcome.ok; ++s) outcome = solver->step();
  EXPECT_FALSE(outcome.ok);
  EXPECT_NE(outcome.message.find("unstable"), std::string::npos) << outcome.message;
  EXPECT_TRUE(all_finite(solver->displacement()));
}

TEST(Extreme, NewmarkConservesEnergyAcrossStiffnessContrastOf1e6) {
  SerialMesh m(unit_cube(4));
  split_materials(m.mesh, 0, 0.5);
  m.local = distribute(m.mesh, m.comm);
  const std::vector<ElasticMaterial> materials{{1.0, 0.3, 1.0}, {1e6, 0.3, 1.0}};
  const double explicit_limit = central_difference_limit(m.local, m.comm, materials).dt;
  std::string error;
  const auto solver = ElasticSolver::create(
      m.local, m.comm, clamped(ElasticScheme::newmark, 100 * explicit_limit, materials),
      free_vibration(), error);
  ASSERT_NE(solver, nullptr) << error;
  const double initial = solver->energy();
  const std::vector<double> u0(solver->displacement().begin(), solver->displacement().end());
  for (int s = 0; s < 40; ++s) ASSERT_TRUE(solver->step().ok);
  EXPECT_NEAR(solver->energy() / initial, 1.0, 1e-6);
  // Conserved energy alone would pass for steps that do nothing. The soft half's slowest mode
  // (shear waves at sqrt(mu / rho) = 0.62 across a clamped 0.5 x 1 x 1 box, omega about 4.8)
  // turns through some 1.9 rad in the 40 steps (t = 0.39), so the body must have moved by a good
  // part of its initial amplitude: a tenth is asked.
  EXPECT_NEAR(solver->time(), 40 * 100 * explicit_limit, 1e-9);
  EXPECT_GT(max_difference(solver->displacement(), u0), 0.1 * max_abs(u0));
  EXPECT_TRUE(all_finite(solver->displacement()));
}

// Without sources the temperature stays within its initial range, for dt far above the explicit
// limit, under both schemes.
TEST(Extreme, ThetaSchemesStayBoundedAcrossConductivityContrastOf1e6) {
  SerialMesh m(unit_cube(4));
  split_materials(m.mesh, 0, 0.5);
  m.local = distribute(m.mesh, m.comm);
  const Separable shape{Shape::sine, Profile::linear};
  for (const ThetaScheme scheme : {ThetaScheme::backward_euler, ThetaScheme::crank_nicolson}) {
    HeatSetup setup;
    setup.materials = {{1.0, 1.0}, {1e6, 1.0}};
    setup.scheme = scheme;
    setup.dt = 0.1;  // the explicit limit is about h^2 / (6 * 1e6), some 1e-8
    setup.fixed_faces = all_faces;
    setup.cg = kTight;
    HeatSolver solver(m.local, m.comm, setup,
                      {[shape](const Vec3& x, double) { return shape.value(x); },
                       [](const Vec3&, double) { return 0.0; }});
    const std::vector<double> initial(solver.temperature().begin(), solver.temperature().end());
    const double initial_max = solver.space().max_abs(initial);
    for (int s = 0; s < 20; ++s) ASSERT_TRUE(solver.step().ok);
    EXPECT_TRUE(all_finite(solver.temperature()));
    EXPECT_LE(solver.space().max_abs(solver.temperature()), initial_max);
    // The bound alone would pass for steps that do nothing. Every mode decays: the slowest one
    // (lambda >= 3 pi^2, the unit cube's with conductivity >= 1) by 1 / (1 + dt lambda) <= 1 / 3.9
    // per backward Euler step; under Crank-Nicolson the soft half's modes (dt lambda from about 6
    // to 100 there) shrink by |1 - dt lambda / 2| / (1 + dt lambda / 2) <= 0.96 per step, 0.44
    // over the 20, where the initial field reaches 0.7 of its maximum.
    if (scheme == ThetaScheme::backward_euler) {
      EXPECT_LT(solver.space().max_abs(solver.temperature()), 1e-3 * initial_max);
    } else {
      EXPECT_GT(max_difference(solver.temperature(), initial), 0.25 * initial_max);
    }
  }
}

// As the Poisson ratio nears 1/2 with the shear modulus fixed, the exact solution of
// measure_locking stays the same, and the growth of the P1 error is locking. It is measured and
// reported, not hidden.
TEST(Extreme, NearlyIncompressibleMaterialRunsAndReportsLocking) {
  const SerialComm comm;
  const LockingMeasurement locking = measure_locking(0.499, comm);
  ASSERT_TRUE(locking.ok) << locking.message;
  std::printf("P1 locking at Poisson ratio 0.499: L2 error %.3e vs %.3e at %.1f, ratio %.2f\n",
              locking.error, locking.reference_error, locking_reference_poisson, locking.ratio);
  ::testing::Test::RecordProperty("locking_ratio", formatted(locking.ratio));
  EXPECT_TRUE(std::isfinite(locking.error));
  EXPECT_GT(locking.ratio, 1.5);
}

// P1 represents linear fields exactly and the time schemes integrate linear profiles exactly, so
// the error is only that of the solver, even on tets with aspect ratio 1000.
void expect_exact_on(const Mesh& mesh) {
  const SerialMesh m(mesh);
  const Separable field{Shape::linear, Profile::linear};
  const RunResult heat =
      run_manufactured_heat(m.local, m.comm, ThetaScheme::backward_euler, 0.1, 0.3, field, kTight);
  ASSERT_TRUE(heat.ok) << heat.message;
  EXPECT_LT(heat.error.max, 1e-8);
  const ElasticMaterial material{};
  const RunResult elastic = run_manufactured_elastic(
      m.local, m.comm, ElasticScheme::newmark, 0.1, 0.3,
      manufactured_elastic(field, {1, 0.5, -0.25}, material.lame(), material.density), material,
      kTight);
  ASSERT_TRUE(elastic.ok) << elastic.message;
  EXPECT_LT(elastic.error.max, 1e-8);
}

TEST(Extreme, FlatPlateWithAspectRatio1000IsExactForLinearFields) {
  expect_exact_on(make_beam({4, 4, 1}, {0, 0, 0}, {1, 1, 2.5e-4}));
}

TEST(Extreme, NeedleWithAspectRatio1000IsExactForLinearFields) {
  expect_exact_on(make_beam({4, 1, 1}, {0, 0, 0}, {1, 2.5e-4, 2.5e-4}));
}

TEST(Extreme, RankWithZeroTetsHasAnEmptyShareAndStillSteps) {
  const Mesh mesh = unit_cube(3);
  const std::vector<double> weights{1, 0, 1};
  const std::vector<std::int32_t> part = partition_rcb(mesh, 3, weights);
  const LocalMesh empty = make_local_mesh(mesh, part, 1);
  EXPECT_EQ(empty.tet_count(), 0u);
  EXPECT_EQ(empty.point_count(), 0u);
  EXPECT_TRUE(empty.halo.empty());
  const SerialComm comm;
  HeatSolver heat(empty, comm, HeatSetup{}, manufactured_heat({Shape::sine, Profile::linear}));
  EXPECT_TRUE(heat.step().ok);
  std::string error;
  const auto elastic = ElasticSolver::create(empty, comm, ElasticSetup{}, free_vibration(), error);
  ASSERT_NE(elastic, nullptr) << error;
  EXPECT_TRUE(elastic->step().ok);
}

}  // namespace
}  // namespace minisolver
