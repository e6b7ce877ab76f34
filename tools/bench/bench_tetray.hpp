// tetray's own figures on one loaded scene: BVH build times (BIH and SAH), memory, and trace
// times and Table-4 counts for each packet size.
#pragma once

#include "bench_results.hpp"
#include "render/core/framebuffer.hpp"
#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct TetrayRun {
  TetrayFigures figures;
  render::Framebuffer image;  // the 16x16 frame, for the depth comparison with Embree
};

// Loads the scene with the default (BIH) policy and measures on it; the renderer's copy is
// freed on return, before the references run.
TetrayRun measure_tetray(const GyroidTwist& scene, const render::Camera& camera);

}  // namespace tetray::bench
