// The extract-then-trace reference, second half: Embree 3 builds its BVH over the contour's
// triangles and traces exactly tetray's rays (render::pixel_direction), shading them with the
// same two-sided Lambert headlight, so both the times and the depth images are comparable.
#pragma once

#include <vector>

#include "bench_reference_vtk.hpp"
#include "render/camera.hpp"

namespace tetray::bench {

struct EmbreeRun {
  double build_ms = 0;  // rtcCommitScene
  double trace_ms = 0;  // the faster of single rays and 16-ray packets
  const char* trace_mode = "";
  std::vector<float> depth;  // view-axis depth per pixel, +infinity for a miss
};

EmbreeRun trace_with_embree(const TriangleSoup& triangles, const render::Camera& camera,
                            int threads);

}  // namespace tetray::bench
