// Where a render step hands its results to the outputs (adaptor/output/): every rank's own
// image before compositing when asked for, and on the writer rank each composited view with its
// log row, annotations and colorbars, queued for the writer thread.
#include <algorithm>
#include <iterator>

#include "adaptor/output/output_files.hpp"
#include "adaptor/step/step_runner.hpp"

namespace tetray {

// Before compositing, which leaves only the writer rank's image defined. Of an orbit, the first
// view.
Status Adaptor::Impl::write_rank_images() {
  for (SceneState& s : scenes_) {
    if (!s.due) continue;
    const PhaseClock::Phase phase(clock_, s.view_times[0].hand_off_ms);
    std::string error =
        write_rank_image(config_.output, s.config.name, s.record.step, comm_.rank, s.images[0]);
    if (!error.empty()) return {StatusCode::io_error, std::move(error)};
  }
  return Status::success();
}

// On the writer rank: the view's image to the writer thread, and its log row kept for the end of
// the call (log_step). The wait for room in the queue is timed apart from the rest.
void Adaptor::Impl::submit_view(SceneState& s, std::size_t k, std::size_t v, StepRecord r,
                                const SceneCounters& sums, std::uint64_t rss) {
  ViewTimes& times = s.view_times[v];
  const PhaseClock::Phase handing(clock_, times.hand_off_ms);
  render::Framebuffer& image = s.images[v];
  r.tets = sums.tets;
  r.kept_tets = sums.kept_tets;
  r.skipped_tets = sums.skipped_tets;
  r.bvh_bytes = sums.bytes;
  r.peak_rss_bytes = rss;
  r.rays = static_cast<std::uint64_t>(image.pixel_count()) * static_cast<std::uint64_t>(comm_.size);
  ImageJob job;
  job.image = std::move(image);
  std::copy(std::begin(s.config.background), std::end(s.config.background), job.background);
  job.record = r;
  job.annotations = annotations_for(s.config, r, color_scales(s));
  // The viewer page goes with the run's first image, not at create: creating writes only what
  // must exist before any step (folders, table headers), so a nearly full disk fails at an image.
  if (!viewer_page_sent_ && config_.output.cinema) {
    for (const config::Scene& scene : config_.scenes) job.viewer_page_scenes.push_back(scene.name);
    viewer_page_sent_ = true;
  }
  if (s.config.orbit.enabled) {
    job.view = static_cast<int>(v);
    job.phi = s.views[v].phi_deg;
    job.theta = s.views[v].theta_deg;
  }
  {
    const PhaseClock::Phase waiting(clock_, times.queue_wait_ms);
    writer_->wait_for_room();
  }
  writer_->submit(std::move(job));
  handed_over_.push_back({k, v, std::move(r)});
}

// What the scene colored through a colormap this step, for its colorbars: the surfaces' color
// field or the volume's transfer function, then the cap.
std::vector<ColorScale> Adaptor::Impl::color_scales(const SceneState& s) const {
  std::vector<ColorScale> scales;
  if (s.colormap != nullptr)
    scales.push_back({s.config.color_by, s.colormap, s.color_range.lo, s.color_range.hi});
  if (s.config.volume) {
    scales.push_back({s.config.field, render::find_colormap(s.config.volume->colormap_name),
                      s.color_range.lo, s.color_range.hi});
  }
  if (s.cap_colormap != nullptr)
    scales.push_back({s.config.shading.cap.field, s.cap_colormap, s.cap_range.lo, s.cap_range.hi});
  return scales;
}

}  // namespace tetray
