#include "errors.hpp"

#include <pybind11/pybind11.h>

namespace py = pybind11;

namespace tetray::python {

void raise_if_failed(const Status& status) {
  if (status.ok()) return;
  // tetray.Error and tetray.PartialWarning are defined in Python (tetray/_errors.py) so that they
  // are ordinary classes; the module is cached in sys.modules after the first import.
  const py::module_ errors = py::module_::import("tetray._errors");
  if (!status.failed()) {
    const py::object warning_type = errors.attr("PartialWarning");
    if (PyErr_WarnEx(warning_type.ptr(), status.message.c_str(), 1) != 0) {
      throw py::error_already_set();
    }
    return;
  }
  const py::object error_type = errors.attr("Error");
  const py::object error = error_type(py::cast(status.code), status.message);
  PyErr_SetObject(error_type.ptr(), error.ptr());
  throw py::error_already_set();
}

}  // namespace tetray::python
