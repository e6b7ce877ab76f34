// The extract-then-trace reference, second half: Embree 3 builds its BVH over the contour's
// triangles and traces exactly tetray's rays (render::pixel_direction), shading them with the
// same two-sided Lambert headlight, so both the times and the depth images are comparable.
#pragma once

#include <memory>
#include <vector>

#include "bench_reference_vtk.hpp"
#include "render/trace/camera.hpp"

namespace tetray::bench {

struct EmbreeRun {
  double build_ms = 0;       // rtcCommitScene
  double trace_ms = 0;       // the faster of single rays and 16-ray packets
  bool packets = false;      // the faster is the packet trace
  bool same_depth = false;   // packets and single rays gave bitwise the same depth image
  std::vector<float> depth;  // view-axis depth per pixel, +infinity for a miss
};

// The Embree call that traces: "rtcIntersect16" for packets, "rtcIntersect1" for single rays.
const char* embree_trace_mode(bool packets);

EmbreeRun trace_with_embree(const TriangleSoup& triangles, const render::Camera& camera,
                            int threads);

// Embree kept across time steps: one device, each step a new scene over that step's triangles
// (kept beside the scene, whose buffers share them), traced into one kept image.
class EmbreeReference {
 public:
  EmbreeReference(const render::Camera& camera, int threads);
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
