// The outcome of a protocol on one rank. An MPI failure is the protocol's own: the ranks may no
// longer be in step, and the caller ends the collective work there. A local failure (this
// rank's own work, such as tracing its shadow rays, ran out of memory) comes back only after
// the rank took part in every collective of the protocol, so the other ranks were not left
// waiting; the caller reports it afterwards.
#pragma once

#include <string>

namespace tetray::render {

struct ProtocolStatus {
  enum class Code { ok, mpi_error, local_error };
  Code code = Code::ok;
  std::string message;

  bool ok() const { return code == Code::ok; }
  static ProtocolStatus success() { return {}; }
};

// MPI's text for an error code (or "MPI error <code>" when MPI has none).
std::string mpi_error_text(int code);

// "<what>: <MPI's text for rc>" as an MPI failure.
ProtocolStatus mpi_failure(const std::string& what, int rc);

}  // namespace tetray::render
