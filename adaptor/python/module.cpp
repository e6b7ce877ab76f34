// The extension module tetray._tetray (the package tetray re-exports it, README "Python").
// pybind11 rather than the C API through ctypes: numpy arrays reach the adaptor's views in place
// with their dtype, shape and layout checked at one boundary (numpy_views.cpp), a failed Status
// becomes tetray.Error there too (errors.cpp), the GIL is released around the collective calls,
// and the Python API carries the C++ API's report and will_render as they are.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <string>

#include "errors.hpp"
#include "mpi_comm.hpp"
#include "py_adaptor.hpp"

namespace py = pybind11;
using namespace pybind11::literals;

namespace tetray::python {
namespace {

void bind_status_code(py::module_& m) {
  py::enum_<StatusCode>(m, "StatusCode",
                        "The code of a call's status (tetray.Error.code for a failed one).")
      .value("ok", StatusCode::ok)
      .value("invalid_argument", StatusCode::invalid_argument)
      .value("config_error", StatusCode::config_error)
      .value("io_error", StatusCode::io_error)
      .value("mpi_error", StatusCode::mpi_error)
      .value("internal_error", StatusCode::internal_error)
      .value("not_initialized", StatusCode::not_initialized)
      .value("partial", StatusCode::partial);
}

void bind_changes(py::module_& m) {
  py::class_<Changes>(m, "Changes", "What changed since the last execute call.")
      .def(py::init([](bool geometry, bool topology, bool fields) {
             return Changes{.geometry = geometry, .topology = topology, .fields = fields};
           }),
           py::kw_only(), "geometry"_a = true, "topology"_a = true, "fields"_a = true)
      .def_readwrite("geometry", &Changes::geometry)
      .def_readwrite("topology", &Changes::topology)
      .def_readwrite("fields", &Changes::fields)
      .def("__repr__", [](const Changes& c) {
        const auto flag = [](bool b) { return b ? std::string("True") : std::string("False"); };
        return "Changes(geometry=" + flag(c.geometry) + ", topology=" + flag(c.topology) +
               ", fields=" + flag(c.fields) + ")";
      });
}

void bind_report(py::module_& m) {
  py::class_<ExecuteReport>(m, "ExecuteReport", "What one execute call did.")
      .def_readonly("rendered", &ExecuteReport::rendered)
      .def_readonly("scenes_rendered", &ExecuteReport::scenes_rendered)
      .def_readonly("seconds_blocked", &ExecuteReport::seconds_blocked)
      .def_readonly("bvh_decision", &ExecuteReport::bvh_decision)
      .def_readonly("tets_skipped", &ExecuteReport::tets_skipped)
      .def_readonly("skipped_scenes", &ExecuteReport::skipped_scenes)
      .def("__repr__", [](const ExecuteReport& r) {
        return "ExecuteReport(rendered=" + std::string(r.rendered ? "True" : "False") +
               ", scenes_rendered=" + std::to_string(r.scenes_rendered) +
               ", seconds_blocked=" + std::to_string(r.seconds_blocked) + ", bvh_decision='" +
               r.bvh_decision + "', tets_skipped=" + std::to_string(r.tets_skipped) + ")";
      });
}

ExecuteReport execute(PyAdaptor& a, std::int64_t step, double time, py::handle points,
                      py::handle tets, py::handle fields, py::handle cells, py::handle displacement,
                      py::handle ghost, py::handle global_ids, const Changes& changes) {
  return a.execute(step, time,
                   {.points = points,
                    .tets = tets,
                    .cells = cells,
                    .fields = fields,
                    .displacement = displacement,
                    .ghost = ghost,
                    .global_ids = global_ids},
                   changes);
}

// Leaving a with-block finalizes; a failure then raises unless an exception is already leaving
// the block, which is not replaced.
bool exit_block(PyAdaptor& a, py::handle exception_type) {
  const Status status = a.finalize();
  if (exception_type.is_none()) raise_if_failed(status);
  return false;
}

void bind_adaptor(py::module_& m) {
  py::class_<PyAdaptor>(m, "Adaptor",
                        "tetray's adaptor on an mpi4py communicator (duplicated). Collective: "
                        "create, execute on rendering steps.")
      .def(py::init(&PyAdaptor::from_file), "comm"_a, "config_path"_a,
           "Reads and validates the YAML config file (str or os.PathLike).")
      .def_static("from_yaml", &PyAdaptor::from_yaml, "comm"_a, "yaml"_a,
                  "The same from the config's YAML text.")
      .def("execute", &execute, "step"_a, "time"_a, "points"_a, "tets"_a = py::none(),
           "fields"_a = py::none(), py::kw_only(), "cells"_a = py::none(),
           "displacement"_a = py::none(), "ghost"_a = py::none(), "global_ids"_a = py::none(),
           "changes"_a = Changes{},
           "One solver step: points (n, 3) float32/float64, tets (m, 4) int32/int64, fields a "
           "dict of name -> (n,) float32/float64, displacement (n, 3), ghost (m,) uint8 "
           "vtkGhostType, global_ids (m,) int64. Instead of tets, cells=(types, offsets, "
           "connectivity) as VTK stores them: (c,) uint8 VTK cell types (10, 12, 13, 14, 24, 71, "
           "72), (c + 1,) offsets and the connectivity, both int32 or int64 (ghost then per "
           "cell). The arrays are read in place during the call and must be C-contiguous. "
           "Returns an ExecuteReport; raises tetray.Error.")
      .def("will_render", &PyAdaptor::will_render, "step"_a, "time"_a,
           "Whether execute(step, time, ...) would render a scene (no MPI, no side effects).")
      .def(
          "finalize", [](PyAdaptor& a) { raise_if_failed(a.finalize()); },
          "Drains the image writer; idempotent. Raises tetray.Error for a writer failure.")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](PyAdaptor& a, py::handle type, py::handle, py::handle) {
        return exit_block(a, type);
      });
}

}  // namespace
}  // namespace tetray::python

PYBIND11_MODULE(_tetray, m) {
  using namespace tetray::python;
  import_mpi4py_api();
  m.doc() = "tetray's adaptor for Python solvers (numpy arrays, mpi4py communicators)";
  bind_status_code(m);
  bind_changes(m);
  bind_report(m);
  bind_adaptor(m);
}
