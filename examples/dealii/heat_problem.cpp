// The heat problem's set-up and what it tells about itself.
#include "heat_problem.hpp"

#include <deal.II/base/mpi.h>
#include <deal.II/grid/grid_generator.h>

#include <algorithm>

#include "heat_state.hpp"

HeatProblem::HeatProblem(MPI_Comm comm, const HeatParameters& parameters)
    : parameters_(parameters), state_(std::make_unique<HeatState>(comm)) {
  dealii::GridGenerator::hyper_cube(state_->triangulation, 0.0, 1.0);  // boundary id 0
  state_->triangulation.refine_global(parameters.initial_refinement);
  refine_around_source(*state_, parameters);
  setup_system(*state_);  // the solution starts at 0
}

HeatProblem::~HeatProblem() = default;

std::uint64_t HeatProblem::global_cells() const {
  return state_->triangulation.n_global_active_cells();
}

std::uint64_t HeatProblem::hanging_nodes() const {
  std::uint64_t local = 0;
  for (const auto dof : state_->owned) {
    // A boundary DoF's line is u = 0, with no entries; a hanging node's names its masters.
    const auto* entries = state_->constraints.get_constraint_entries(dof);
    local += entries != nullptr && !entries->empty();
  }
  return dealii::Utilities::MPI::sum(local, state_->comm);
}

double HeatProblem::max_temperature() const {
  double local = 0.0;  // the temperature is >= 0
  for (const auto dof : state_->owned) local = std::max(local, double(state_->solution[dof]));
  return dealii::Utilities::MPI::max(local, state_->comm);
}
