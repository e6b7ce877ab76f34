// tetray.Adaptor: the C++ Adaptor with Python's conventions. Failed statuses raise tetray.Error,
// bad arguments raise TypeError or ValueError, and the collective calls run without the GIL.
#pragma once

#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>
#include <string_view>

#include "numpy_views.hpp"
#include "tetray/adaptor.hpp"

namespace tetray::python {

class PyAdaptor {
 public:
  // Collective over `comm` (an mpi4py communicator), like Adaptor::create.
  static std::unique_ptr<PyAdaptor> from_file(pybind11::handle comm, pybind11::handle path);
  static std::unique_ptr<PyAdaptor> from_yaml(pybind11::handle comm, std::string_view yaml);

  ExecuteReport execute(std::int64_t step, double time, const StepArguments& arguments,
                        const Changes& changes);
  bool will_render(std::int64_t step, double time) const;
  Status finalize();

 private:
  explicit PyAdaptor(std::unique_ptr<Adaptor> adaptor);
  void join_failed_step(std::int64_t step, double time);
  std::unique_ptr<Adaptor> adaptor_;
};

}  // namespace tetray::python
