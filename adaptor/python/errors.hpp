// Failed statuses as Python exceptions: tetray.Error (a RuntimeError) with .code, a
// tetray.StatusCode, and .message, the adaptor's text. A partial status (some scenes skipped, the
// rest rendered) is no failure: it is a tetray.PartialWarning, Python's way of saying "done, but".
#pragma once

#include "tetray/adaptor.hpp"

namespace tetray::python {

// Throws (as pybind11::error_already_set) tetray.Error for a failed status, warns for a partial
// one (throwing if the warning filter turned it into an error); returns otherwise.
void raise_if_failed(const Status& status);

}  // namespace tetray::python
