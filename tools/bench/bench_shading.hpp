// The shading modalities on the benchmark scene (Wald et al. 2007, §7, Fig. 7): the frame with a
// shadowing point light (trace with its term, shadow rays from the hit points, shading), with a
// clip box that removes half the volume, and with smooth normals (and the vertex gradients they
// need, computed once per update), each timed in turn with the plain frame in the same run and
// reported as a ratio to it. The smooth step (update, gradients, frame) is also set beside the
// flat one (update, frame), which is what a solver pays per rendered step.
#pragma once

#include <json/json.h>

#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct ShadingFigures {
  double plain_ms = 0;
  double shadow_ms = 0;  // headlight + a shadowing point light
  double clip_ms = 0;    // a clip box keeping x <= 0
  double smooth_ms = 0;
  double gradients_ms = 0;       // the smooth frame's vertex gradients, once per update
  double update_ms = 0;          // a step's geometry and field update (refit), without them
  double reached_fraction = 0;   // of the hit pixels, those the point light reaches (rays traced)
  double shadowed_fraction = 0;  // of those, in the shadow of the point light
};

// The default packets (render::TraceOptions), one rank.
ShadingFigures measure_shading(const GyroidTwist& scene, const render::Camera& camera);
void print_shading(const ShadingFigures& figures);

// The smooth step over the flat step, both with the update of a new step.
double smooth_step_ratio(const ShadingFigures& figures);
Json::Value shading_json(const ShadingFigures& figures);

}  // namespace tetray::bench
