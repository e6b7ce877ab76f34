#include "numpy_views.hpp"

#include <pybind11/numpy.h>

#include <cstdint>
#include <optional>

namespace py = pybind11;

namespace tetray::python {
namespace {

std::string type_name(py::handle obj) { return py::str(py::type::handle_of(obj).attr("__name__")); }

std::string shape_text(const py::array& a) {
  std::string text = "(";
  for (py::ssize_t d = 0; d < a.ndim(); ++d) {
    text += (d > 0 ? ", " : "") + std::to_string(a.shape(d));
  }
  return text + (a.ndim() == 1 ? ",)" : ")");
}

py::array as_array(py::handle obj, const std::string& name) {
  if (!py::isinstance<py::array>(obj)) {
    throw py::type_error(name + ": expected a numpy.ndarray, got " + type_name(obj));
  }
  return py::reinterpret_borrow<py::array>(obj);
}

template <typename T>
bool has_dtype(const py::array& a) {
  // dtype equality includes the byte order: a big-endian array is not read as native.
  return a.dtype().equal(py::dtype::of<T>());
}

[[noreturn]] void wrong_dtype(const py::array& a, const std::string& name, const char* wanted) {
  throw py::type_error(name + ": dtype " + std::string(py::str(a.dtype())) + " is not " + wanted +
                       " in native byte order");
}

ScalarType scalar_type(const py::array& a, const std::string& name) {
  if (has_dtype<double>(a)) return ScalarType::float64;
  if (has_dtype<float>(a)) return ScalarType::float32;
  wrong_dtype(a, name, "float32 or float64");
}

IndexType index_type(const py::array& a, const std::string& name) {
  if (has_dtype<std::int64_t>(a)) return IndexType::int64;
  if (has_dtype<std::int32_t>(a)) return IndexType::int32;
  wrong_dtype(a, name, "int32 or int64");
}

template <typename T>
void require_dtype(const py::array& a, const std::string& name, const char* wanted) {
  if (!has_dtype<T>(a)) wrong_dtype(a, name, wanted);
}

// `columns` 0: one dimension; `rows`: the required first extent, when another array fixes it.
void require_shape(const py::array& a, const std::string& name, py::ssize_t columns,
                   std::optional<py::ssize_t> rows, const std::string& wanted) {
  const bool ok = columns == 0 ? a.ndim() == 1 : a.ndim() == 2 && a.shape(1) == columns;
  if (!ok || (rows && a.shape(0) != *rows)) {
    throw py::value_error(name + ": shape " + shape_text(a) + " is not " + wanted);
  }
}

// tetray reads the array's memory as it is; making it contiguous would be a copy per call that
// the caller should see and decide on.
void require_in_place(const py::array& a, const std::string& name) {
  constexpr int kAligned = py::detail::npy_api::NPY_ARRAY_ALIGNED_;
  if ((a.flags() & py::array::c_style) == 0) {
    throw py::value_error(name +
                          ": the array is not C-contiguous (tetray reads it in place and "
                          "does not copy); pass numpy.ascontiguousarray(" +
                          name + ")");
  }
  if ((a.flags() & kAligned) == 0) throw py::value_error(name + ": the array is not aligned");
}

std::string rows_text(const char* letter, py::ssize_t rows, const char* what) {
  return std::string(letter) + " = " + std::to_string(rows) + " " + what;
}

PointsView read_points(const StepArguments& args) {
  const py::array xyz = as_array(args.points, "points");
  PointsView points;
  points.type = scalar_type(xyz, "points");
  require_shape(xyz, "points", 3, std::nullopt, "(n, 3)");
  require_in_place(xyz, "points");
  points.xyz = xyz.data();
  points.count = static_cast<std::size_t>(xyz.shape(0));
  if (!args.displacement.is_none()) {
    const py::array u = as_array(args.displacement, "displacement");
    points.displacement_type = scalar_type(u, "displacement");
    require_shape(u, "displacement", 3, xyz.shape(0),
                  "(n, 3) with " + rows_text("n", xyz.shape(0), "points"));
    require_in_place(u, "displacement");
    points.displacement = u.data();
  }
  return points;
}

// An optional per-tet (or per-cell) array of dtype T, or null.
template <typename T>
const T* per_tet(py::handle obj, const char* name, const char* dtype, py::ssize_t tets) {
  if (obj.is_none()) return nullptr;
  const py::array a = as_array(obj, name);
  require_dtype<T>(a, name, dtype);
  require_shape(a, name, 0, tets, "(m,) with " + rows_text("m", tets, "tets"));
  require_in_place(a, name);
  return static_cast<const T*>(a.data());
}

TetsView read_tets(const StepArguments& args) {
  const py::array connectivity = as_array(args.tets, "tets");
  TetsView tets;
  tets.type = index_type(connectivity, "tets");
  require_shape(connectivity, "tets", 4, std::nullopt, "(m, 4)");
  require_in_place(connectivity, "tets");
  tets.connectivity = connectivity.data();
  const py::ssize_t count = connectivity.shape(0);
  tets.count = static_cast<std::size_t>(count);
  tets.ghost = per_tet<std::uint8_t>(args.ghost, "ghost", "uint8", count);
  tets.global_ids = per_tet<std::int64_t>(args.global_ids, "global_ids", "int64", count);
  return tets;
}

template <typename Index>
std::int64_t last_value(const py::array& a) {
  return static_cast<const Index*>(a.data())[a.shape(0) - 1];
}

// cells = (types, offsets, connectivity): (c,) uint8 VTK cell types, (c + 1,) offsets and the
// connectivity they index, both int32 or both int64.
CellsView read_cells(const StepArguments& args) {
  if (!py::isinstance<py::tuple>(args.cells) || py::len(args.cells) != 3) {
    throw py::type_error("cells: expected a tuple (types, offsets, connectivity), got " +
                         type_name(args.cells));
  }
  const auto parts = py::reinterpret_borrow<py::tuple>(args.cells);
  const py::array types = as_array(parts[0], "cells types");
  const py::array offsets = as_array(parts[1], "cells offsets");
  const py::array connectivity = as_array(parts[2], "cells connectivity");
  require_dtype<std::uint8_t>(types, "cells types", "uint8");
  require_shape(types, "cells types", 0, std::nullopt, "(c,)");
  CellsView cells;
  cells.type = index_type(offsets, "cells offsets");
  if (index_type(connectivity, "cells connectivity") != cells.type) {
    throw py::type_error("cells: offsets and connectivity must have the same dtype");
  }
  const py::ssize_t count = types.shape(0);
  require_shape(offsets, "cells offsets", 0, count + 1,
                "(c + 1,) with " + rows_text("c", count, "cells"));
  require_shape(connectivity, "cells connectivity", 0, std::nullopt, "(k,)");
  for (const py::array* a : {&types, &offsets, &connectivity}) require_in_place(*a, "cells");
  const std::int64_t length = cells.type == IndexType::int64 ? last_value<std::int64_t>(offsets)
                                                             : last_value<std::int32_t>(offsets);
  if (length != connectivity.shape(0)) {
    throw py::value_error("cells: offsets[-1] is " + std::to_string(length) +
                          " but the connectivity has " + std::to_string(connectivity.shape(0)) +
                          " entries");
  }
  cells.types = static_cast<const std::uint8_t*>(types.data());
  cells.offsets = offsets.data();
  cells.connectivity = connectivity.data();
  cells.count = static_cast<std::size_t>(count);
  cells.ghost = per_tet<std::uint8_t>(args.ghost, "ghost", "uint8", count);
  return cells;
}

void read_mesh(const StepArguments& args, MeshView& mesh) {
  mesh.points = read_points(args);
  if (args.cells.is_none() == args.tets.is_none()) {
    throw py::value_error("pass either tets or cells (not both, not neither)");
  }
  if (args.tets.is_none()) {
    if (!args.global_ids.is_none()) {
      throw py::value_error(
          "global_ids: per-tet ids need tets; with cells ties resolve by "
          "position");
    }
    mesh.cells = read_cells(args);
  } else {
    mesh.tets = read_tets(args);
  }
}

// The adaptor checks each field's length against the points where a scene uses it.
void read_fields(py::handle fields, StepViews& views) {
  if (fields.is_none()) return;
  if (!py::isinstance<py::dict>(fields)) {
    throw py::type_error("fields: expected a dict of name -> numpy.ndarray, got " +
                         type_name(fields));
  }
  const auto dict = py::reinterpret_borrow<py::dict>(fields);
  views.field_names.reserve(dict.size());
  for (const auto& [key, value] : dict) {
    if (!py::isinstance<py::str>(key)) {
      throw py::type_error("fields: a key is a " + type_name(key) + ", not a str");
    }
    const std::string& field = views.field_names.emplace_back(py::str(key));
    const std::string name = "fields['" + field + "']";
    const py::array values = as_array(value, name);
    const ScalarType type = scalar_type(values, name);
    require_shape(values, name, 0, std::nullopt, "(n,)");
    require_in_place(values, name);
    views.fields.push_back({field, values.data(), type, static_cast<std::size_t>(values.shape(0))});
    views.field_arrays.push_back(values);
  }
}

}  // namespace

StepViews read_step_views(const StepArguments& arguments) {
  StepViews views;
  read_mesh(arguments, views.mesh);
  read_fields(arguments.fields, views);
  return views;
}

}  // namespace tetray::python
