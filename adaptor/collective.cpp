#include "collective.hpp"

#include <vector>

#include "render/composite/global_reduce.hpp"

namespace tetray {
namespace {

int reduce_to_root(const Communicator& c, int root, std::span<std::uint64_t> values, MPI_Op op) {
  if (c.size == 1 || values.empty()) return MPI_SUCCESS;
  void* send = c.rank == root ? MPI_IN_PLACE : values.data();
  return MPI_Reduce(send, values.data(), static_cast<int>(values.size()), MPI_UINT64_T, op, root,
                    c.comm);
}

}  // namespace

int reduce_sum_to_root(const Communicator& c, int root, std::span<SceneCounters> counters) {
  std::vector<std::uint64_t> packed = pack(counters);
  const int rc = reduce_to_root(c, root, packed, MPI_SUM);
  unpack(packed, counters);
  return rc;
}

int reduce_max_to_root(const Communicator& c, int root, std::uint64_t& value) {
  return reduce_to_root(c, root, std::span(&value, 1), MPI_MAX);
}

int broadcast_status(const Communicator& c, int root, Status& status) {
  if (c.size == 1) return MPI_SUCCESS;
  std::uint64_t head[2] = {static_cast<std::uint64_t>(status.code), status.message.size()};
  if (int rc = MPI_Bcast(head, 2, MPI_UINT64_T, root, c.comm); rc != MPI_SUCCESS) return rc;
  status.code = static_cast<StatusCode>(head[0]);
  status.message.resize(head[1]);
  return MPI_Bcast(status.message.data(), static_cast<int>(head[1]), MPI_CHAR, root, c.comm);
}

Status agree(const Communicator& c, const Status& local, StepRanges* ranges) {
  if (c.size == 1) return local;
  // The lowest failing rank, as the union of the failing ranks' numbers, travels first.
  std::vector<render::ValueRange> packed(1);
  if (!local.ok()) packed[0].include(c.rank);
  if (ranges != nullptr) {
    const std::vector<render::ValueRange> own = pack(*ranges);
    packed.insert(packed.end(), own.begin(), own.end());
  }
  if (int rc = render::global_ranges(packed, c.comm); rc != MPI_SUCCESS) {
    return {StatusCode::mpi_error, "agreeing on the step's outcome: " + mpi_error_text(rc)};
  }
  if (ranges != nullptr) unpack(std::span(packed).subspan(1), *ranges);
  if (packed[0].empty()) return Status::success();
  const int root = static_cast<int>(packed[0].lo);
  Status status = local;
  if (int rc = broadcast_status(c, root, status); rc != MPI_SUCCESS) {
    return {StatusCode::mpi_error,
            "sharing rank " + std::to_string(root) + "'s error: " + mpi_error_text(rc)};
  }
  status.message = "rank " + std::to_string(root) + ": " + status.message;
  return status;
}

std::string mpi_error_text(int code) {
  char text[MPI_MAX_ERROR_STRING];
  int length = 0;
  if (MPI_Error_string(code, text, &length) != MPI_SUCCESS)
    return "MPI error " + std::to_string(code);
  return std::string(text, static_cast<std::size_t>(length));
}

}  // namespace tetray
