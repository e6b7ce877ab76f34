#include "minisolver/locking.hpp"

#include "minisolver/local_mesh.hpp"
#include "minisolver/manufactured_run.hpp"

namespace minisolver {
namespace {

// Tight enough that the error measured is the discretization's, not the solver's.
const CgSettings kTight{1e-12, 50000};

RunResult solenoidal_run(const LocalMesh& mesh, const Comm& comm, double poisson) {
  const ElasticMaterial material{2 * (1 + poisson), poisson, 1.0};  // shear modulus 1
  return run_manufactured_elastic(
      mesh, comm, ElasticScheme::newmark, 0.05, 0.1,
      manufactured_solenoidal(Profile::linear, material.lame(), material.density), material,
      kTight);
}

}  // namespace

LockingMeasurement measure_locking(double poisson, const Comm& comm, int cells) {
  const LocalMesh mesh = distribute(make_beam({cells, cells, cells}, {0, 0, 0}, {1, 1, 1}), comm);
  const RunResult reference = solenoidal_run(mesh, comm, locking_reference_poisson);
  if (!reference.ok) return {false, reference.message};
  const RunResult run = solenoidal_run(mesh, comm, poisson);
  if (!run.ok) return {false, run.message};
  return {true, {}, run.error.l2, reference.error.l2, run.error.l2 / reference.error.l2};
}

}  // namespace minisolver
