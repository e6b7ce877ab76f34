// deal.II's objects of the heat problem, shared by the files of its one translation unit
// (the CMake target compiles them as a unity build: deal.II's headers are compiled once).
#pragma once

#include <deal.II/base/index_set.h>
#include <deal.II/distributed/tria.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/trilinos_vector.h>

#include <vector>

#include "heat_parameters.hpp"

struct HeatState {
  explicit HeatState(MPI_Comm comm)
      : comm(comm),
        // deal.II's 2:1 balance, at vertices too: a coarse cell's edge or face meets at most one
        // level finer, the only hanging nodes being at edge midpoints and face centres.
        triangulation(comm, dealii::Triangulation<3>::limit_level_difference_at_vertices),
        fe(1),
        dofs(triangulation) {}

  MPI_Comm comm;
  dealii::parallel::distributed::Triangulation<3> triangulation;
  dealii::FE_Q<3> fe;
  dealii::DoFHandler<3> dofs;
  dealii::IndexSet owned;     // the DoFs this rank owns
  dealii::IndexSet relevant;  // those of its owned and ghost cells
  // Hanging nodes and u = 0 on the boundary.
  dealii::AffineConstraints<double> constraints;
  dealii::TrilinosWrappers::SparseMatrix matrix;  // M + dt K
  dealii::TrilinosWrappers::MPI::Vector rhs;      // owned
  // The current temperature with ghost values, constraints distributed: the values at hanging
  // nodes are their constrained interpolation.
  dealii::TrilinosWrappers::MPI::Vector solution;
  // The DoF of each point of the last exported mesh (Q1: one per vertex).
  std::vector<dealii::types::global_dof_index> point_dofs;
};

// Distributes the DoFs on the current mesh and sizes the constraints, matrix and vectors.
void setup_system(HeatState& state);
// Refines the cells near the source's starting point, `levels` times.
void refine_around_source(HeatState& state, const HeatParameters& parameters);
