// The update figures of one scene: the cost of bringing a new time step into the renderer
// (field only, geometry + field, rebuild) next to its memcpy bound, the per-step in-situ total,
// and the rebuild policy's decisions over the gyroid-twist steps and after a strong deformation.
#pragma once

#include "bench_results.hpp"
#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct StepOptions {
  int steps = 5;                  // t = 0, 0.1, ... including the start
  int threads = 1;                // of the reference's Embree device
  bool reference_packets = true;  // the reference traces in 16-ray packets, else single rays
};

// `start` is the scene at t = 0, where the twist is zero: its points are the reference that
// later steps deform.
RefitFigures measure_refit(const GyroidTwist& start, const render::Camera& camera,
                           const StepOptions& options);

}  // namespace tetray::bench
