// The error-against-run-time study of volume rendering (docs/architecture.md §8): tetray's
// exact per-tet integral against fixed-step sampling along the same walk
// (render/walk/fixed_step.hpp) at steps of 1, 1/2, 1/4, ... of the mean tet edge, each frame's
// time and its image error against a dense reference: the same discrete sum at a step 16 times
// finer than the finest compared, accumulated in double. No early termination anywhere, so only
// the integrators differ.
#pragma once

#include <string>
#include <vector>

#include "render/core/framebuffer.hpp"
#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"
#include "tools/bench_common/image_error.hpp"

namespace tetray::bench {

struct DvrStudyRow {
  std::string step;  // "exact", or the sampling step in mean tet edges
  double ms = 0;     // best of kRepetitions frames
  ImageError error;  // its color_mean and color_max (RGBA)
};

struct DvrStudy {
  double mean_edge = 0;       // of the mesh's tets, world units
  double reference_step = 0;  // in mean tet edges
  double reference_ms = 0;
  std::vector<DvrStudyRow> rows;  // exact first, then the steps coarse to fine
};

// `halvings` + 1 fixed steps: 1, 1/2, ..., 1/2^halvings mean edges.
DvrStudy run_dvr_study(const GyroidTwist& scene, const render::Camera& camera, int halvings = 4);

// Columns step,ms,mean_error,max_error; throws on a write error.
void write_dvr_study_csv(const DvrStudy& study, const std::string& path);
void print_dvr_study(const DvrStudy& study);

}  // namespace tetray::bench
