// One backward Euler step: (M + dt K) u_new = M u_old + dt F(t_new), assembled cell by cell with
// the constraints applied as the entries are added, then CG with a Jacobi preconditioner.
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/vector.h>

#include "heat_problem.hpp"
#include "heat_source.hpp"
#include "heat_state.hpp"

namespace {

void assemble_step(HeatState& state, const HeatParameters& parameters, double time) {
  using namespace dealii;
  const auto center = source_center(time, parameters.steps * parameters.dt);
  const double dt = parameters.dt;
  const QGauss<3> quadrature(2);
  FEValues<3> values(
      state.fe, quadrature,
      update_values | update_gradients | update_quadrature_points | update_JxW_values);
  const unsigned int per_cell = state.fe.n_dofs_per_cell();
  FullMatrix<double> cell_matrix(per_cell, per_cell);
  dealii::Vector<double> cell_rhs(per_cell);
  std::vector<double> old_values(quadrature.size());
  std::vector<types::global_dof_index> cell_dofs(per_cell);

  state.matrix = 0;
  state.rhs = 0;
  for (const auto& cell : state.dofs.active_cell_iterators()) {
    if (!cell->is_locally_owned()) continue;
    values.reinit(cell);
    values.get_function_values(state.solution, old_values);  // the step before
    cell_matrix = 0;
    cell_rhs = 0;
    for (unsigned int q = 0; q < quadrature.size(); ++q) {
      const Point<3>& x = values.quadrature_point(q);
      const double f = source_value(center, parameters.source_width, x[0], x[1], x[2]);
      const double weight = values.JxW(q);
      for (unsigned int i = 0; i < per_cell; ++i) {
        for (unsigned int j = 0; j < per_cell; ++j) {
          cell_matrix(i, j) += (values.shape_value(i, q) * values.shape_value(j, q) +
                                dt * values.shape_grad(i, q) * values.shape_grad(j, q)) *
                               weight;
        }
        cell_rhs(i) += (old_values[q] + dt * f) * values.shape_value(i, q) * weight;
      }
    }
    cell->get_dof_indices(cell_dofs);
    state.constraints.distribute_local_to_global(cell_matrix, cell_rhs, cell_dofs, state.matrix,
                                                 state.rhs);
  }
  state.matrix.compress(VectorOperation::add);
  state.rhs.compress(VectorOperation::add);
}

unsigned int solve_step(HeatState& state) {
  using namespace dealii;
  TrilinosWrappers::MPI::Vector solution(state.owned, state.comm);
  solution = state.solution;  // the step before as the first guess
  // A tight tolerance: the solution, and so the images, must not depend on the partition.
  SolverControl control(2000, 1e-12 * state.rhs.l2_norm());
  SolverCG<TrilinosWrappers::MPI::Vector> cg(control);
  TrilinosWrappers::PreconditionJacobi jacobi;
  jacobi.initialize(state.matrix);
  cg.solve(state.matrix, solution, state.rhs, jacobi);
  // Hanging nodes and the boundary get their constrained values, then the ghosts their owners'.
  state.constraints.distribute(solution);
  state.solution = solution;
  return control.last_step();
}

}  // namespace

unsigned int HeatProblem::advance(double time) {
  assemble_step(*state_, parameters_, time);
  return solve_step(*state_);
}
