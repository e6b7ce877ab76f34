#include "render/parallel/protocol_status.hpp"

#include <mpi.h>

namespace tetray::render {

std::string mpi_error_text(int code) {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  if (MPI_Error_string(code, text, &length) != MPI_SUCCESS)
    return "MPI error " + std::to_string(code);
  return std::string(text, static_cast<std::size_t>(length));
}

ProtocolStatus mpi_failure(const std::string& what, int rc) {
  return {ProtocolStatus::Code::mpi_error, what + ": " + mpi_error_text(rc)};
}

}  // namespace tetray::render
