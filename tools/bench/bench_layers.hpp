// Transparency on the benchmark scene (Wald et al. 2007, §8.5: its cost grows with the layers
// traced): the frame with two transparent isosurfaces peeled to 4 layers, and the frame of all
// shading modalities together (a shadowing point light, a clip box removing half the volume and
// the two transparent surfaces, every layer shadowed), each timed in turn with the plain frame of
// the same run and reported as a ratio to it, with the layers traced per primary ray; and the
// same two surfaces opaque, which separates what peeling costs from what a second isovalue costs.
#pragma once

#include <json/json.h>

#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct LayerFigures {
  double plain_ms = 0;        // the bench surface, opaque
  double opaque_pair_ms = 0;  // the two surfaces of the transparent frame, opaque
  double transparent_ms = 0;  // two surfaces at opacity 0.5, max_layers 4: trace and blend
  double all_ms = 0;          // and a shadowing point light and the half clip box
  double layers_per_ray = 0;  // of the transparent frame: fragments / rays of the image
  double all_layers_per_ray = 0;
};

// The default packets (render::TraceOptions), one rank.
LayerFigures measure_layers(const GyroidTwist& scene, const render::Camera& camera);
void print_layers(const LayerFigures& figures);
Json::Value layers_json(const LayerFigures& figures);

}  // namespace tetray::bench
