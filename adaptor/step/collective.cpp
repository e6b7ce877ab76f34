#include "adaptor/step/collective.hpp"

#include <vector>

#include "render/parallel/global_reduce.hpp"

namespace tetray {

int broadcast_status(const Communicator& c, int root, Status& status) {
  if (c.size == 1) return MPI_SUCCESS;
  std::uint64_t head[2] = {static_cast<std::uint64_t>(status.code), status.message.size()};
  if (int rc = MPI_Bcast(head, 2, MPI_UINT64_T, root, c.comm); rc != MPI_SUCCESS) return rc;
  status.code = static_cast<StatusCode>(head[0]);
  status.message.resize(head[1]);
  return MPI_Bcast(status.message.data(), static_cast<int>(head[1]), MPI_CHAR, root, c.comm);
}

namespace {

// A flag per rank as a range: the union over the ranks holds the lowest flagged rank.
render::ValueRange flag(bool raised, int rank) {
  render::ValueRange r;
  if (raised) r.include(rank);
  return r;
}

// `root`'s text on every rank, prefixed with "rank <root>: ".
Status share_from(const Communicator& c, int root, Status& text) {
  if (int rc = broadcast_status(c, root, text); rc != MPI_SUCCESS) {
    return {StatusCode::mpi_error,
            "sharing rank " + std::to_string(root) + "'s error: " + mpi_error_text(rc)};
  }
  text.message = "rank " + std::to_string(root) + ": " + text.message;
  return Status::success();
}

}  // namespace

Status agree(const Communicator& c, const Status& local, StepRanges* ranges, SceneSkips* skips) {
  if (c.size == 1) return local;
  // The lowest failing rank and, per scene, the lowest rank that skips it travel first.
  std::vector<render::ValueRange> packed{flag(!local.ok(), c.rank)};
  const std::size_t scene_count = skips != nullptr ? skips->size() : 0;
  for (std::size_t k = 0; k < scene_count; ++k) {
    packed.push_back(flag(!(*skips)[k].empty(), c.rank));
  }
  if (ranges != nullptr) {
    const std::vector<render::ValueRange> own = pack(*ranges);
    packed.insert(packed.end(), own.begin(), own.end());
  }
  if (int rc = render::global_ranges(packed, c.comm); rc != MPI_SUCCESS) {
    return {StatusCode::mpi_error, "agreeing on the step's outcome: " + mpi_error_text(rc)};
  }
  if (ranges != nullptr) unpack(std::span(packed).subspan(1 + scene_count), *ranges);
  for (std::size_t k = 0; k < scene_count; ++k) {
    if (packed[1 + k].empty()) continue;
    Status reason{StatusCode::partial, (*skips)[k]};
    if (Status shared = share_from(c, static_cast<int>(packed[1 + k].lo), reason); !shared.ok()) {
      return shared;
    }
    (*skips)[k] = std::move(reason.message);
  }
  if (packed[0].empty()) return Status::success();
  Status status = local;
  if (Status shared = share_from(c, static_cast<int>(packed[0].lo), status); !shared.ok()) {
    return shared;
  }
  return status;
}

Status to_status(render::ProtocolStatus status) {
  switch (status.code) {
    case render::ProtocolStatus::Code::ok:
      return Status::success();
    case render::ProtocolStatus::Code::mpi_error:
      return {StatusCode::mpi_error, std::move(status.message)};
    case render::ProtocolStatus::Code::local_error:
      break;
  }
  return {StatusCode::internal_error, std::move(status.message)};
}

}  // namespace tetray
