// The adaptor's life around its steps: one volume per distinct isosurface field at creation, the
// outputs prepared at start, the writer drained at finalize.
#include "adaptor/step/step_runner.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "adaptor/output/output_files.hpp"
#include "adaptor/step/thread_budget.hpp"
#include "render/isa/isa.hpp"

namespace tetray {

Adaptor::Impl::Impl(Communicator comm, config::Config config)
    : comm_(comm),
      config_(std::move(config)),
      threads_(config_.threads > 0 ? config_.threads : default_thread_count()),
      arena_(threads_),
      probes_(config_.probes) {
  for (const config::Scene& s : config_.scenes) {
    SceneState state(s);
    const auto same_field = [&](const FieldVolume& v) { return v.field() == s.field; };
    const auto found = std::find_if(volumes_.begin(), volumes_.end(), same_field);
    state.volume = static_cast<std::size_t>(found - volumes_.begin());
    if (found == volumes_.end()) volumes_.emplace_back(s.field);
    if (!s.color_by.empty()) state.colormap = render::find_colormap(s.colormap_name);
    if (!s.shading.cap.field.empty())
      state.cap_colormap = render::find_colormap(s.shading.cap.colormap_name);
    scenes_.push_back(std::move(state));
  }
  skipped_.assign(volumes_.size(), 0);
  walks_.resize(volumes_.size());
  shared_gradients_.resize(volumes_.size());
  skips_.resize(scenes_.size());
  ranges_.scenes.resize(scenes_.size());
}

Adaptor::Impl::~Impl() {
  finalize();
  int finalized = 0;
  MPI_Finalized(&finalized);
  if (!finalized && comm_.comm != MPI_COMM_NULL) MPI_Comm_free(&comm_.comm);
}

Status Adaptor::Impl::start() {
  const Status status =
      agree(comm_, guarded("create", [&] { return prepare_outputs_on_this_rank(); }));
  started_ = status.ok();
  if (started_ && is_writer() && !config_.output.quiet) {
    std::printf("tetray: kernels %s\n", render::isa::choice_note().c_str());
    std::fflush(stdout);
  }
  return status;
}

Status Adaptor::Impl::prepare_outputs_on_this_rank() {
  const config::Output& output = config_.output;
  std::string error;
  if (is_writer()) error = prepare_outputs(output, config_.scenes);
  if (error.empty() && is_writer()) error = probes_.prepare(output.directory);
  if (error.empty() && output.per_rank_images) {
    error = prepare_rank_image_directories(output, config_.scenes, comm_.rank);
  }
  if (!error.empty()) return {StatusCode::io_error, error};
  if (is_writer()) writer_ = std::make_unique<ImageWriter>(output, threads_);
  return Status::success();
}

Status Adaptor::Impl::take_pending_error() {
  Status pending = std::exchange(pending_, Status::success());
  if (pending.ok() && writer_ && writer_->has_error()) {
    pending = {StatusCode::io_error, writer_->take_error()};
  }
  return pending;
}

// Collective (for a started adaptor): the writer rank drains its queue, and every rank gets the
// writer's last errors and its own pending one.
Status Adaptor::Impl::finalize() {
  if (finalized_) return Status::success();
  finalized_ = true;
  if (!started_) return Status::success();
  const Status status = guarded("finalize", [&] {
    if (writer_) writer_->finish();
    Status pending = take_pending_error();
    writer_.reset();
    return pending;
  });
  int mpi_finalized = 0;
  MPI_Finalized(&mpi_finalized);
  // Destroyed after MPI_Finalize without a finalize call: nothing to agree with.
  if (mpi_finalized) return status;
  return agree(comm_, status);
}

}  // namespace tetray
