// Observed orders of convergence against manufactured solutions: about 2 in space for the L2
// error of P1 tets, 1 in time for backward Euler, 2 for Crank-Nicolson, Newmark and central
// differences. Space ladders use fields the time schemes integrate (almost) exactly, time ladders
// fields P1 represents exactly, so each ladder sees one error source.
#include <gtest/gtest.h>

#include "minisolver/manufactured_run.hpp"
#include "serial_cube.hpp"

namespace minisolver {
namespace {

using testing::observed_orders;
using testing::SerialMesh;
using testing::unit_cube;

const CgSettings kTight{1e-12, 20000};
const ElasticMaterial kMaterial{1.0, 0.3, 1.0};
const Vec3 kDirection{1.0, 0.5, -0.25};

std::vector<double> heat_space_ladder(ThetaScheme scheme) {
  std::vector<double> errors;
  for (const int n : {4, 8, 16}) {
    const SerialMesh m(unit_cube(n));
    const RunResult r = run_manufactured_heat(m.local, m.comm, scheme, 0.02, 0.1,
                                              {Shape::sine, Profile::linear}, kTight);
    EXPECT_TRUE(r.ok) << r.message;
    errors.push_back(r.error.l2);
  }
  return errors;
}

std::vector<double> heat_time_ladder(ThetaScheme scheme) {
  const SerialMesh m(unit_cube(3));
  std::vector<double> errors;
  for (const double dt : {0.1, 0.05, 0.025}) {
    const RunResult r = run_manufactured_heat(m.local, m.comm, scheme, dt, 0.5,
                                              {Shape::linear, Profile::oscillating}, kTight);
    EXPECT_TRUE(r.ok) << r.message;
    errors.push_back(r.error.l2);
  }
  return errors;
}

std::vector<double> elastic_time_ladder(ElasticScheme scheme, double dt0) {
  const SerialMesh m(unit_cube(3));
  const ElasticData data = manufactured_elastic({Shape::linear, Profile::oscillating}, kDirection,
                                                kMaterial.lame(), kMaterial.density);
  std::vector<double> errors;
  for (const double dt : {dt0, dt0 / 2, dt0 / 4}) {
    const RunResult r =
        run_manufactured_elastic(m.local, m.comm, scheme, dt, 0.5, data, kMaterial, kTight);
    EXPECT_TRUE(r.ok) << r.message;
    errors.push_back(r.error.l2);
  }
  return errors;
}

void expect_orders_near(const std::vector<double>& errors, double expected, double tolerance) {
  for (const double order : observed_orders(errors)) EXPECT_NEAR(order, expected, tolerance);
}

// The coarsest mesh (n = 4) is not yet asymptotic: its order is only bounded below.
void expect_space_orders(const std::vector<double>& errors) {
  const std::vector<double> orders = observed_orders(errors);
  EXPECT_GT(orders.front(), 1.6);
  EXPECT_NEAR(orders.back(), 2.0, 0.2);
}

TEST(Convergence, HeatIsSecondOrderInSpace) {
  expect_space_orders(heat_space_ladder(ThetaScheme::backward_euler));
}

TEST(Convergence, BackwardEulerIsFirstOrderInTime) {
  expect_orders_near(heat_time_ladder(ThetaScheme::backward_euler), 1.0, 0.15);
}

TEST(Convergence, CrankNicolsonIsSecondOrderInTime) {
  expect_orders_near(heat_time_ladder(ThetaScheme::crank_nicolson), 2.0, 0.15);
}

TEST(Convergence, ElasticityIsSecondOrderInSpace) {
  const ElasticData data = manufactured_elastic({Shape::sine, Profile::linear}, kDirection,
                                                kMaterial.lame(), kMaterial.density);
  std::vector<double> errors;
  for (const int n : {4, 8, 16}) {
    const SerialMesh m(unit_cube(n));
    const RunResult r = run_manufactured_elastic(m.local, m.comm, ElasticScheme::newmark, 0.05, 0.1,
                                                 data, kMaterial, kTight);
    ASSERT_TRUE(r.ok) << r.message;
    errors.push_back(r.error.l2);
  }
  expect_space_orders(errors);
}

TEST(Convergence, NewmarkIsSecondOrderInTime) {
  expect_orders_near(elastic_time_ladder(ElasticScheme::newmark, 0.1), 2.0, 0.15);
}

TEST(Convergence, CentralDifferencesAreSecondOrderInTime) {
  const SerialMesh m(unit_cube(3));
  const double limit = central_difference_limit(m.local, m.comm, {kMaterial}).dt;
  expect_orders_near(elastic_time_ladder(ElasticScheme::central_difference, 0.5 * limit), 2.0,
                     0.15);
}

}  // namespace
}  // namespace minisolver
