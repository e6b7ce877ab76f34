// Clip caps on the benchmark scene (Wald et al. 2007, §7): the frame cut by a plane through the
// centre facing the eye, without and with a cap of the scene's field (render/walk/clip_cap.hpp),
// timed in turn with the plain frame in the same run and reported as ratios to it.
#pragma once

#include <json/json.h>

#include <cstddef>

#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct CapFigures {
  double plain_ms = 0;
  double clip_ms = 0;       // the plane alone
  double cap_ms = 0;        // the plane and its cap: the trace, then the cap pass
  double cap_fraction = 0;  // of the pixels, showing the cap
};

// The default packets (render::TraceOptions), one rank.
CapFigures measure_cap(const GyroidTwist& scene, const render::Camera& camera);
void print_cap(const CapFigures& figures);
Json::Value cap_json(const CapFigures& figures);

}  // namespace tetray::bench
