// Volume rendering against the work it does (issue targets on the performance page): a transfer
// function of three thin shells, like the demo's, against the opaque isosurface frame of the
// same field at the shells' values; a dense transfer function (non-zero everywhere, the VTK
// peer's, bench_vtk_volume.hpp); each with empty-space skipping (the default) and walking every
// tet, the largest difference between the two images, tet steps per second and core, and jumps
// over empty space per ray.
#pragma once

#include <json/json.h>

#include "render/scene/camera.hpp"
#include "render/walk/volume_render.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct VolumeCase {
  double ms = 0;                   // with empty-space skipping
  double walk_all_ms = 0;          // every tet of every ray's way walked
  double mtet_steps_per_core = 0;  // tets walked per second and thread, millions, skipping
  double busy_fraction = 0;        // tets not empty for the transfer function
  double jumps_per_ray = 0;
  double tets_per_ray = 0;           // walked, skipping
  double walk_all_tets_per_ray = 0;  // walked, every tet
  double max_difference = 0;         // largest RGBA difference of the two images
};

struct VolumeFigures {
  double iso_ms = 0;  // the opaque isosurfaces at the shells' values, one frame
  VolumeCase shells;
  VolumeCase dense;
  VolumeCase sparse;  // one thin shell near the field's maximum: small blobs, empty elsewhere
  int threads = 1;
};

// Three thin shells around the isovalues kShellValues (clear elsewhere).
render::VolumeRenderOptions shell_options();
// One thin shell where the field nears its maximum.
render::VolumeRenderOptions sparse_options();
// Non-zero everywhere (bench_walk.hpp's dvr_options with termination 1).
render::VolumeRenderOptions dense_options();

VolumeFigures measure_volume(const GyroidTwist& scene, const render::Camera& camera, int threads);
void print_volume(const VolumeFigures& figures);
Json::Value volume_json(const VolumeFigures& figures);

}  // namespace tetray::bench
