#include "tetray/adaptor.hpp"

#include <new>

#include "adaptor/config/config_parse.hpp"
#include "adaptor/step/step_runner.hpp"
#include "render/isa/isa.hpp"

namespace tetray {
namespace {

Status internal(const char* call, const char* what) {
  return {StatusCode::internal_error, std::string(call) + ": " + what};
}

Status duplicate(MPI_Comm comm, Communicator& out) {
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized) return {StatusCode::not_initialized, "create: MPI is not initialized"};
  if (comm == MPI_COMM_NULL) return {StatusCode::invalid_argument, "create: comm is MPI_COMM_NULL"};
  if (int rc = MPI_Comm_dup(comm, &out.comm); rc != MPI_SUCCESS) {
    return {StatusCode::mpi_error, "create: MPI_Comm_dup: " + mpi_error_text(rc)};
  }
  // Errors on the adaptor's own communicator come back as codes instead of aborting the job.
  MPI_Comm_set_errhandler(out.comm, MPI_ERRORS_RETURN);
  MPI_Comm_rank(out.comm, &out.rank);
  MPI_Comm_size(out.comm, &out.size);
  return Status::success();
}

}  // namespace

Adaptor::Adaptor(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
Adaptor::~Adaptor() = default;

// Collective: every rank checks that its CPU runs the kernels and parses (the text or the file)
// for the communicator's size, the ranks agree on the outcome, and the writer rank prepares the
// outputs. Whatever fails on one rank before an agreement is that agreement's outcome, so no rank
// is left waiting in it.
template <typename Parse>
std::unique_ptr<Adaptor> Adaptor::create_with(MPI_Comm comm, Parse&& parse, Status& status) {
  Communicator c;
  status = duplicate(comm, c);
  if (!status.ok()) return nullptr;
  std::unique_ptr<Impl> impl;
  try {
    status = guarded("create", [&] {
      // First: a CPU without x86-64-v2 would fault in the first kernel of a dispatch build.
      if (std::string lacks = render::isa::kernels_refusal(); !lacks.empty())
        return Status{StatusCode::internal_error, "create: " + lacks};
      config::ParseResult parsed = parse(c.size);
      if (!parsed.config) return Status{StatusCode::config_error, parsed.error};
      impl = std::make_unique<Impl>(c, std::move(*parsed.config));
      return Status::success();
    });
    status = agree(c, status);
    if (status.ok()) status = impl->start();
    if (status.ok()) return std::unique_ptr<Adaptor>(new Adaptor(std::move(impl)));
  } catch (const std::exception& e) {
    status = internal("create", e.what());
  }
  // The communicator is the Impl's to free once it exists.
  if (!impl) MPI_Comm_free(&c.comm);
  return nullptr;
}

std::unique_ptr<Adaptor> Adaptor::create(MPI_Comm comm, const std::string& config_path,
                                         Status& status) {
  return create_with(
      comm, [&](int rank_count) { return config::load_config_file(config_path, rank_count); },
      status);
}

std::unique_ptr<Adaptor> Adaptor::create_from_yaml(MPI_Comm comm, std::string_view yaml,
                                                   Status& status) {
  return create_with(
      comm, [&](int rank_count) { return config::parse_config(yaml, "<yaml string>", rank_count); },
      status);
}

bool Adaptor::will_render(std::int64_t step, double time) const {
  return impl_->will_render(step, time);
}

Status Adaptor::execute(std::int64_t step, double time, const MeshView& mesh,
                        std::span<const FieldView> fields, const Changes& changes,
                        ExecuteReport* report) {
  try {
    return impl_->execute(step, time, mesh, fields, changes, report);
  } catch (const std::bad_alloc&) {
    return internal("execute", "out of memory");
  } catch (const std::exception& e) {
    return internal("execute", e.what());
  }
}

Status Adaptor::execute_failed(std::int64_t step, double time, Status error, const Changes& changes,
                               ExecuteReport* report) {
  try {
    return impl_->execute_failed(step, time, std::move(error), changes, report);
  } catch (const std::exception& e) {
    return internal("execute", e.what());
  }
}

Status Adaptor::finalize() {
  try {
    return impl_->finalize();
  } catch (const std::exception& e) {
    return internal("finalize", e.what());
  }
}

}  // namespace tetray
