// numpy arrays as the adaptor's views, without copies: each array must already have the layout
// the adaptor reads (a dtype it takes, the shape, C-contiguous, aligned); anything else is a
// TypeError (dtype, not an array) or ValueError (shape, layout) naming the argument, never a
// silent copy.
#pragma once

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "tetray/adaptor.hpp"

namespace tetray::python {

// The Python arguments of one execute call; None for the optional ones.
struct StepArguments {
  pybind11::handle points;        // (n, 3) float32/float64
  pybind11::handle tets;          // (m, 4) int32/int64, or None with cells
  pybind11::handle cells;         // (types, offsets, connectivity) as CellsView, or None
  pybind11::handle fields;        // dict name -> (n,) float32/float64, or None
  pybind11::handle displacement;  // (n, 3) float32/float64
  pybind11::handle ghost;         // (m,) uint8 vtkGhostType flags, per tet or per cell
  pybind11::handle global_ids;    // (m,) int64, with tets only
};

// Views into the arguments' arrays. The field arrays are referenced here, so that a dict changed
// by another thread while execute runs without the GIL cannot free them.
struct StepViews {
  MeshView mesh;
  std::vector<std::string> field_names;  // the FieldViews' names point into these
  std::vector<FieldView> fields;
  std::vector<pybind11::object> field_arrays;
};

StepViews read_step_views(const StepArguments& arguments);

}  // namespace tetray::python
