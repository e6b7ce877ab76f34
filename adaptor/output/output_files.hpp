// The files of docs/architecture.md §3 on the writer rank: images
// `<dir>/<scene>/<scene>_<step>[_view<view>].exr|png` (written atomically by render/image), the
// Cinema database (spec D: time, phi, theta, scene, step, then the files)
// `<dir>/<scene>.cdb/data.csv` and the timing log `<dir>/tetray_log.csv`; with per_rank_images,
// every rank's own image
// `<dir>/<scene>/ranks/<scene>_<step>_rank<rank>.png`. Every function returns an error message
// (empty on success); a failed append leaves the file as it was, so nothing already written is
// damaged, and a run killed at any moment leaves whole images and whole lines (line_file.hpp).
// A run into a directory that holds an earlier run's files keeps them: the Cinema table goes on
// listing the earlier images still on disk, the log keeps the earlier rows.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "adaptor/config/config.hpp"
#include "adaptor/output/step_record.hpp"
#include "render/annotate/annotate.hpp"
#include "render/core/framebuffer.hpp"

namespace tetray {

// `view` is the index of an orbit's view (`<scene>_<step>_view<3 digits>`); -1 for a scene
// without an orbit.
std::string image_path(const std::string& directory, const std::string& scene, std::int64_t step,
                       const char* extension, int view = -1);
std::string rank_image_path(const std::string& directory, const std::string& scene,
                            std::int64_t step, int rank);
std::string log_path(const std::string& directory);
std::string cinema_path(const std::string& directory, const std::string& scene);

// Before the first step, on the writer rank: creates the folders, removes the temporary files a
// killed earlier run left of the files this one writes, and opens the log and the Cinema tables:
// a new table gets its header; an existing one with this run's header keeps its rows (the Cinema
// table those whose images are all still on disk) and loses a last line a kill tore; one with
// another header starts afresh.
std::string prepare_outputs(const config::Output& output, const std::vector<config::Scene>& scenes);

// Creates `<dir>/<scene>/ranks` for every scene and removes the stale temporary files of this
// rank's images there. Every rank calls it: its output directory may be one that only it sees.
std::string prepare_rank_image_directories(const config::Output& output,
                                           const std::vector<config::Scene>& scenes, int rank);

// This rank's un-composited image as PNG, without the background: what the rank did not cover
// stays transparent, so the ranks' layers can be laid over each other.
std::string write_rank_image(const config::Output& output, const std::string& scene,
                             std::int64_t step, int rank, const render::Framebuffer& image);

// One composited image with what the writer needs to file it.
struct ImageJob {
  render::Framebuffer image;
  float background[4] = {0, 0, 0, 0};
  StepRecord record;
  render::Annotations annotations;  // empty: the image is written as composited
  // The view of an orbit: its index (-1 without an orbit) and angles in degrees (Cinema's phi
  // and theta columns).
  int view = -1;
  double phi = 0, theta = 0;
  // Non-empty for the run's first image: index.html is written for these scenes, after the
  // image and its rows (so an image's error is the one reported).
  std::vector<std::string> viewer_page_scenes;
};

// Background, annotations, image files, Cinema row; fills the record's writer timings and hits
// for its log row (which the writer appends once the step's execute has returned,
// image_writer.hpp). A step whose image is already on disk (rendered again) replaces its Cinema
// row instead of adding a second one.
std::string write_image_job(const config::Output& output, ImageJob& job);

}  // namespace tetray
