// The exact trace against Embree's, timed in turn: the two traces alternate, a frame of each per
// round, so that both see the same moments of a shared machine and their ratio (the trace
// targets) does not follow whatever load fell on one of them alone.
#pragma once

#include "bench_reference_vtk.hpp"
#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct TraceInTurn {
  int rounds = 0;
  double tetray_ms = 0;  // the default packets, best of the rounds
  double embree_ms = 0;  // Embree's faster trace of the extracted triangles, best of the rounds
};

// `packets`: Embree traces in its coherent 16-ray packets, else in single rays (whichever was
// the faster in trace_with_embree).
TraceInTurn trace_in_turn(const GyroidTwist& scene, const TriangleSoup& triangles,
                          const render::Camera& camera, int threads, bool packets);

}  // namespace tetray::bench
