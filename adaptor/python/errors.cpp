#include "errors.hpp"

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace tetray::python {

void raise_if_failed(const Status& status) {
  if (status.ok()) return;
  // tetray.Error is defined in Python (tetray/_errors.py) so that it is an ordinary exception
  // class with its own constructor; the module is cached in sys.modules after the first import.
  const py::object error_type = py::module_::import("tetray._errors").attr("Error");
  const py::object error = error_type(py::cast(status.code), status.message);
  PyErr_SetObject(error_type.ptr(), error.ptr());
  throw py::error_already_set();
}

}  // namespace tetray::python
