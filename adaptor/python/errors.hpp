// Failed statuses as Python exceptions: tetray.Error (a RuntimeError) with .code, a
// tetray.StatusCode, and .message, the adaptor's text.
#pragma once

#include "tetray/adaptor.hpp"

namespace tetray::python {

// Throws (as pybind11::error_already_set) tetray.Error for a failed status; returns otherwise.
void raise_if_failed(const Status& status);

}  // namespace tetray::python
