// Run under mpirun: heat (Crank-Nicolson) and elasticity (Newmark and central differences) on a
// partitioned beam give the same solution as one process on the whole mesh, to 1e-10 relative.
// Optional argument: per-rank partition weights, e.g. "1,0,1,1" for a rank with zero tets.
// Exits non-zero on a mismatch.
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "minisolver/manufactured_run.hpp"

namespace minisolver {
namespace {

const CgSettings kTight{1e-13, 50000};
constexpr int kSteps = 5;

std::vector<double> parse_weights(const char* text) {
  std::vector<double> w;
  std::stringstream in(text);
  for (std::string item; std::getline(in, item, ',');) w.push_back(std::stod(item));
  return w;
}

// The largest difference on this rank's owned points, relative to the largest serial value.
double relative_mismatch(const LocalMesh& local, std::span<const double> distributed,
                         const LocalMesh& whole, std::span<const double> serial, int components,
                         const Comm& comm) {
  double difference = 0, scale = 0;
  for (std::size_t p = 0; p < local.point_count(); ++p) {
    if (!local.owned[p]) continue;
    const auto g = static_cast<std::size_t>(local.point_ids[p]);  // whole-mesh ids are global ids
    for (int i = 0; i < components; ++i)
      difference = std::max(difference,
                            std::abs(distributed[components * p + i] - serial[components * g + i]));
  }
  for (std::size_t g = 0; g < whole.point_count(); ++g)
    for (int i = 0; i < components; ++i)
      scale = std::max(scale, std::abs(serial[components * g + i]));
  return comm.max(difference) / scale;
}

template <class Solver>
void advance(Solver& solver) {
  for (int s = 0; s < kSteps; ++s)
    if (!solver.step().ok) MPI_Abort(MPI_COMM_WORLD, 2);
}

double heat_mismatch(const LocalMesh& local, const LocalMesh& whole, const Comm& comm) {
  HeatSetup setup;
  setup.dt = 0.05;
  setup.fixed_faces = all_faces;
  setup.cg = kTight;
  const HeatData data = manufactured_heat({Shape::sine, Profile::oscillating});
  const SerialComm self;
  HeatSolver distributed(local, comm, setup, data), serial(whole, self, setup, data);
  advance(distributed);
  advance(serial);
  return relative_mismatch(local, distributed.temperature(), whole, serial.temperature(), 1, comm);
}

double elastic_mismatch(ElasticScheme scheme, const LocalMesh& local, const LocalMesh& whole,
                        const Comm& comm) {
  ElasticSetup setup;
  setup.scheme = scheme;
  setup.fixed_faces = x_min;
  setup.cg = kTight;
  const SerialComm self;
  setup.dt = scheme == ElasticScheme::newmark
                 ? 0.05
                 : 0.5 * central_difference_limit(whole, self, setup.materials).dt;
  const ElasticData data{[](const Vec3&, double) { return Kinematics{}; },
                         [](const Vec3& x, double t) {
                           return Vec3{0, -x[0] * (1 + t), 0.1};
                         }};
  std::string error;
  const auto distributed = ElasticSolver::create(local, comm, setup, data, error);
  const auto serial = ElasticSolver::create(whole, self, setup, data, error);
  if (!distributed || !serial) MPI_Abort(MPI_COMM_WORLD, 3);
  advance(*distributed);
  advance(*serial);
  return relative_mismatch(local, distributed->displacement(), whole, serial->displacement(), 3,
                           comm);
}

int check(int argc, char** argv) {
  const MpiComm comm(MPI_COMM_WORLD);
  const std::vector<double> weights = argc > 1 ? parse_weights(argv[1]) : std::vector<double>{};
  const Mesh mesh = make_beam({8, 4, 4}, {0, 0, 0}, {2, 1, 1});
  const LocalMesh local = distribute(mesh, comm, weights);
  const LocalMesh whole = distribute(mesh, SerialComm{});
  const double tets = comm.sum(static_cast<double>(local.tet_count()));
  const double heat = heat_mismatch(local, whole, comm);
  const double newmark = elastic_mismatch(ElasticScheme::newmark, local, whole, comm);
  const double central = elastic_mismatch(ElasticScheme::central_difference, local, whole, comm);
  if (comm.rank() == 0)
    std::printf(
        "%d ranks (%zu tets on rank 0, %g in all): relative mismatch heat %.2e, newmark %.2e, "
        "central differences %.2e\n",
        comm.size(), local.tet_count(), tets, heat, newmark, central);
  const bool ok = tets == static_cast<double>(mesh.tet_count()) && heat < 1e-10 &&
                  newmark < 1e-10 && central < 1e-10;
  return ok ? 0 : 1;
}

}  // namespace
}  // namespace minisolver

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  const int code = minisolver::check(argc, argv);
  MPI_Finalize();
  return code;
}
