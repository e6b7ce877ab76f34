// DoFs, constraints and the matrix's sparsity on the current mesh.
#include <deal.II/base/function.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparsity_tools.h>
#include <deal.II/numerics/vector_tools.h>

#include "heat_state.hpp"

void setup_system(HeatState& state) {
  using namespace dealii;
  state.dofs.distribute_dofs(state.fe);
  state.owned = state.dofs.locally_owned_dofs();
  DoFTools::extract_locally_relevant_dofs(state.dofs, state.relevant);

  state.constraints.clear();
  state.constraints.reinit(state.relevant);
  DoFTools::make_hanging_node_constraints(state.dofs, state.constraints);
  VectorTools::interpolate_boundary_values(state.dofs, 0, Functions::ZeroFunction<3>(),
                                           state.constraints);
  state.constraints.close();

  DynamicSparsityPattern pattern(state.relevant);
  DoFTools::make_sparsity_pattern(state.dofs, pattern, state.constraints, false);
  SparsityTools::distribute_sparsity_pattern(pattern, state.owned, state.comm, state.relevant);
  state.matrix.reinit(state.owned, state.owned, pattern, state.comm);
  state.rhs.reinit(state.owned, state.comm);
  state.solution.reinit(state.owned, state.relevant, state.comm);
}
