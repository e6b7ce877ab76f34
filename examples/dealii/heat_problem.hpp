// The deal.II solver: du/dt - div(grad u) = f on the unit cube, u = 0 on its boundary and at
// t = 0, f the moving Gaussian of heat_source.hpp; Q1 elements on a
// parallel::distributed::Triangulation<3> of hexahedra, backward Euler, Trilinos matrices and
// vectors, CG with a Jacobi preconditioner. The mesh is adapted (Kelly estimator, refine and
// coarsen, solution transferred) when the caller asks. Only standard types cross this header.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <memory>

#include "heat_parameters.hpp"
#include "local_hex_mesh.hpp"

struct HeatState;  // deal.II's objects (heat_state.hpp)

class HeatProblem {
 public:
  // The cube, refined globally and then around the source's starting point, with its DoFs.
  HeatProblem(MPI_Comm comm, const HeatParameters& parameters);
  ~HeatProblem();
  HeatProblem(const HeatProblem&) = delete;
  HeatProblem& operator=(const HeatProblem&) = delete;

  // One backward Euler step that ends at `time`; returns the CG iterations it took.
  unsigned int advance(double time);
  // Refines where the Kelly estimator is largest and coarsens where smallest, then carries the
  // solution over to the new mesh. The topology changes; the solution is current after it.
  void adapt_mesh();

  // This rank's owned and ghost active cells as VTK hexahedra (types, offsets, connectivity,
  // ghost flags) over the vertices they use. Call after each change of the mesh.
  void export_mesh(LocalHexMesh& mesh);
  // The temperature at the points of the last export_mesh, hanging nodes included (their
  // constrained values).
  void export_temperature(LocalHexMesh& mesh) const;

  std::uint64_t global_cells() const;  // active cells over all ranks
  // The vertices whose value the hanging-node constraints set (at the midpoint of a coarser
  // cell's edge or the centre of its face), over all ranks.
  std::uint64_t hanging_nodes() const;
  double max_temperature() const;  // over all ranks

 private:
  HeatParameters parameters_;
  std::unique_ptr<HeatState> state_;
};
