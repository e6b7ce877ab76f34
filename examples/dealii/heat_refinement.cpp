// The mesh follows the source: refined around it before the first step, then adapted to the
// temperature (Kelly estimator) every few steps, the solution carried over by
// p::d::SolutionTransfer. Cells stay between the initial level and parameters.max_level.
//
// An adaptation refines, then coarsens, in two passes, so that the new mesh is the same on any
// number of ranks (the images are compared byte for byte across rank counts). Refining alone
// gives the same mesh on every partition; coarsening does not in deal.II 9.4, even alone and
// with no family split between ranks: each rank keeps or drops coarsen flags for the 2:1 balance
// from the cells it sees (measured with one combined pass and the same flags everywhere: 2444
// cells on one rank, 2479 and 2486 on two and three, after the first adaptation). So the
// coarsening pass flags only families whose coarsening needs no neighbour to change: every cell
// at their vertices is at most at the children's level.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/distributed/grid_refinement.h>
#include <deal.II/distributed/solution_transfer.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/error_estimator.h>

#include <algorithm>

#include "heat_problem.hpp"
#include "heat_source.hpp"
#include "heat_state.hpp"

namespace {

// Kelly's estimate per active cell of the rank (ghost and artificial cells get 0).
dealii::Vector<float> kelly_indicators(const HeatState& state) {
  using namespace dealii;
  dealii::Vector<float> indicators(state.triangulation.n_active_cells());
  KellyErrorEstimator<3>::estimate(state.dofs, QGauss<2>(2), {}, state.solution, indicators,
                                   ComponentMask(), nullptr, numbers::invalid_unsigned_int,
                                   state.triangulation.locally_owned_subdomain());
  return indicators;
}

// Applies the flags set on the mesh and carries the solution over to the new one.
void execute_with_transfer(HeatState& state) {
  using namespace dealii;
  parallel::distributed::SolutionTransfer<3, TrilinosWrappers::MPI::Vector> transfer(state.dofs);
  state.triangulation.prepare_coarsening_and_refinement();
  transfer.prepare_for_coarsening_and_refinement(state.solution);
  state.triangulation.execute_coarsening_and_refinement();  // and repartitions
  setup_system(state);
  TrilinosWrappers::MPI::Vector interpolated(state.owned, state.comm);
  transfer.interpolate(interpolated);
  state.constraints.distribute(interpolated);  // the new hanging nodes
  state.solution = interpolated;
}

void clear_refine_flags_at(HeatState& state, unsigned int max_level) {
  for (const auto& cell : state.triangulation.active_cell_iterators()) {
    if (cell->is_locally_owned() && cell->level() >= static_cast<int>(max_level)) {
      cell->clear_refine_flag();
    }
  }
}

// Keeps the coarsen flag only on whole families of this rank, above the initial level, whose
// coarsening leaves every neighbour within one level of the parent whatever the neighbours do:
// no cell at the family's vertices is finer than the children.
void keep_independent_coarsening(HeatState& state, unsigned int min_level) {
  auto& tria = state.triangulation;
  std::vector<int> finest_at_vertex(tria.n_vertices(), 0);
  for (const auto& cell : tria.active_cell_iterators()) {
    if (cell->is_artificial()) continue;  // every neighbour of an owned cell is owned or ghost
    for (const unsigned int v : cell->vertex_indices()) {
      int& finest = finest_at_vertex[cell->vertex_index(v)];
      finest = std::max(finest, cell->level());
    }
  }
  for (const auto& cell : tria.active_cell_iterators()) {
    if (!cell->is_locally_owned() || !cell->coarsen_flag_set()) continue;
    if (cell->level() <= static_cast<int>(min_level)) {
      cell->clear_coarsen_flag();
      continue;
    }
    const auto parent = cell->parent();
    bool keep = true;
    for (unsigned int c = 0; keep && c < parent->n_children(); ++c) {
      const auto child = parent->child(c);
      keep = child->is_active() && child->is_locally_owned() && child->coarsen_flag_set();
      for (const unsigned int v : child->vertex_indices()) {
        keep = keep && finest_at_vertex[child->vertex_index(v)] <= cell->level();
      }
    }
    if (!keep) cell->clear_coarsen_flag();
  }
}

}  // namespace

void refine_around_source(HeatState& state, const HeatParameters& parameters) {
  const auto center = source_center(0.0, parameters.steps * parameters.dt);
  const dealii::Point<3> source(center[0], center[1], center[2]);
  for (unsigned int level = 0; level < parameters.source_refinement; ++level) {
    // Only geometry decides, so every partition refines the same cells.
    for (const auto& cell : state.triangulation.active_cell_iterators()) {
      if (!cell->is_locally_owned()) continue;
      if (cell->center().distance(source) < 2 * parameters.source_width + cell->diameter() / 2) {
        cell->set_refine_flag();
      }
    }
    clear_refine_flags_at(state, parameters.max_level);
    state.triangulation.execute_coarsening_and_refinement();
  }
}

void HeatProblem::adapt_mesh() {
  using dealii::parallel::distributed::GridRefinement::refine_and_coarsen_fixed_fraction;
  HeatState& state = *state_;
  // Refine the cells that hold the largest half of the estimated error...
  refine_and_coarsen_fixed_fraction(state.triangulation, kelly_indicators(state), 0.5, 0.0);
  clear_refine_flags_at(state, parameters_.max_level);
  execute_with_transfer(state);
  // ...then coarsen those that hold the smallest half of it, on the refined mesh.
  refine_and_coarsen_fixed_fraction(state.triangulation, kelly_indicators(state), 0.0, 0.5);
  keep_independent_coarsening(state, parameters_.initial_refinement);
  execute_with_transfer(state);
}
