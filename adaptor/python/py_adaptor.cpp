#include "py_adaptor.hpp"

#include <string>

#include "errors.hpp"
#include "mpi_comm.hpp"

namespace py = pybind11;

namespace tetray::python {
namespace {

template <typename Create>
std::unique_ptr<Adaptor> create_without_gil(Create&& create) {
  Status status;
  std::unique_ptr<Adaptor> adaptor;
  {
    const py::gil_scoped_release release;
    adaptor = create(status);
  }
  raise_if_failed(status);
  return adaptor;
}

}  // namespace

PyAdaptor::PyAdaptor(std::unique_ptr<Adaptor> adaptor) : adaptor_(std::move(adaptor)) {}

std::unique_ptr<PyAdaptor> PyAdaptor::from_file(py::handle comm, py::handle path) {
  const MPI_Comm c = communicator(comm);
  const std::string file = py::str(py::module_::import("os").attr("fspath")(path));
  return std::unique_ptr<PyAdaptor>(new PyAdaptor(
      create_without_gil([&](Status& status) { return Adaptor::create(c, file, status); })));
}

std::unique_ptr<PyAdaptor> PyAdaptor::from_yaml(py::handle comm, std::string_view yaml) {
  const MPI_Comm c = communicator(comm);
  return std::unique_ptr<PyAdaptor>(new PyAdaptor(create_without_gil(
      [&](Status& status) { return Adaptor::create_from_yaml(c, yaml, status); })));
}

ExecuteReport PyAdaptor::execute(std::int64_t step, double time, const StepArguments& arguments,
                                 const Changes& changes) {
  StepViews views;
  try {
    views = read_step_views(arguments);
  } catch (...) {
    join_failed_step(step, time);
    throw;
  }
  ExecuteReport report;
  Status status;
  {
    // The arrays stay referenced by the caller's frame (and the field arrays by `views`) while
    // the adaptor reads them without the GIL.
    const py::gil_scoped_release release;
    status = adaptor_->execute(step, time, views.mesh, views.fields, changes, &report);
  }
  raise_if_failed(status);
  return report;
}

// An argument rejected on this rank must not leave the other ranks waiting in the step's
// collective. On a rendering step this rank still takes part, declaring a point it does not give,
// which the adaptor's validation rejects on every rank: the other ranks raise tetray.Error
// naming this rank. Off-trigger steps do no MPI, so there is nothing to join.
void PyAdaptor::join_failed_step(std::int64_t step, double time) {
  if (!adaptor_->will_render(step, time)) return;
  MeshView unusable;
  unusable.points.count = 1;
  const py::gil_scoped_release release;
  adaptor_->execute(step, time, unusable, {});
}

bool PyAdaptor::will_render(std::int64_t step, double time) const {
  return adaptor_->will_render(step, time);
}

Status PyAdaptor::finalize() {
  const py::gil_scoped_release release;
  return adaptor_->finalize();
}

}  // namespace tetray::python
