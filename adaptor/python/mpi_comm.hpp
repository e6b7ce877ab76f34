// mpi4py communicators as MPI_Comm handles, through mpi4py's C API (the communicator object's
// own handle: no Fortran round trip, no copy).
#pragma once

#include <mpi.h>
#include <pybind11/pybind11.h>

namespace tetray::python {

// Imports mpi4py.MPI (which initializes MPI) and its C API; call once at module import.
void import_mpi4py_api();

// The handle of `comm`, an mpi4py.MPI.Comm; a TypeError names anything else.
MPI_Comm communicator(pybind11::handle comm);

}  // namespace tetray::python
