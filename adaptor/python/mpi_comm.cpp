#include "mpi_comm.hpp"

// mpi4py's header defines its C API as function pointers local to this translation unit, so the
// import and every use live here.
#include <mpi4py/mpi4py.h>

#include <string>

namespace py = pybind11;

namespace tetray::python {

void import_mpi4py_api() {
  if (import_mpi4py() < 0) throw py::error_already_set();
}

MPI_Comm communicator(py::handle comm) {
  if (!PyObject_TypeCheck(comm.ptr(), &PyMPIComm_Type)) {
    throw py::type_error("comm: expected an mpi4py.MPI.Comm, got " +
                         std::string(py::str(py::type::handle_of(comm).attr("__name__"))));
  }
  MPI_Comm* handle = PyMPIComm_Get(comm.ptr());
  if (handle == nullptr) throw py::error_already_set();
  return *handle;
}

}  // namespace tetray::python
