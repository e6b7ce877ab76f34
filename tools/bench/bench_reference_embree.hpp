// The extract-then-trace reference, second half: Embree 3 builds its BVH over the contour's
// triangles and traces exactly tetray's rays (render::pixel_direction), shading them with the
// same two-sided Lambert headlight, so both the times and the depth images are comparable.
#pragma once

#include <memory>
#include <vector>

#include "bench_reference_vtk.hpp"
#include "render/scene/camera.hpp"

namespace tetray::bench {

// How Embree builds a scene. `static_scene`: its default build (medium quality), for the trace
// comparisons (a high-quality build, with spatial splits, traced no faster: 27.0 against 27.1 ms
// at 1M tets, 32.0 against 31.9 ms at 4M, while building 5x longer). `new_step`: a dynamic scene
// at low quality, Embree's setting for geometry rebuilt every frame, for the in-situ step: its
// build took a quarter to a half of the default's on the gyroid-twist (6-11 against 19-22 ms at
// 1M tets, 15-23 against 50-56 ms at 4M), its trace about 3% longer, the same depth image.
enum class EmbreeBuild { static_scene, new_step };

struct EmbreeRun {
  double build_ms = 0;       // rtcCommitScene
  double trace_ms = 0;       // the faster of single rays and 16-ray packets
  bool packets = false;      // the faster is the packet trace
  bool same_depth = false;   // packets and single rays gave bitwise the same depth image
  std::vector<float> depth;  // view-axis depth per pixel, +infinity for a miss
};

// The Embree call that traces: "rtcIntersect16" for packets, "rtcIntersect1" for single rays.
const char* embree_trace_mode(bool packets);

// Embree's default build (EmbreeBuild::static_scene) and its traces.
EmbreeRun trace_with_embree(const TriangleSoup& triangles, const render::Camera& camera,
                            int threads);

// The new-step build (EmbreeBuild::new_step) of the same triangles and its trace in the mode
// `static_run` found faster, checked against that run's depth image.
struct EmbreeStepBuild {
  double build_ms = 0;
  double trace_ms = 0;
  std::size_t depth_differs = 0;  // pixels whose depth is not bitwise static_run's
};
EmbreeStepBuild step_build_with_embree(const TriangleSoup& triangles, const render::Camera& camera,
                                       int threads, const EmbreeRun& static_run);

// Embree kept across time steps: one device, each step a new scene over that step's triangles
// (kept beside the scene, whose buffers share them), traced into one kept image.
class EmbreeReference {
 public:
  EmbreeReference(const render::Camera& camera, int threads,
                  EmbreeBuild build = EmbreeBuild::static_scene);
  ~EmbreeReference();
  EmbreeReference(const EmbreeReference&) = delete;
  EmbreeReference& operator=(const EmbreeReference&) = delete;

  // Builds the scene over `triangles`, replacing the last one; times the commit alone.
  double build_ms(TriangleSoup triangles);
  // One trace of the last scene built into the kept image, in 16-ray packets or single rays.
  double trace_ms(bool packets);
  const std::vector<float>& depth() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace tetray::bench
