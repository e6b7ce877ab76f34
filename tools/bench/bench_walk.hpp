// The walk stage's figures (docs/architecture.md §8) on the gyroid-twist scene: face adjacency
// build time and bytes per tet in the Tet20 and Tet16 forms (Aman et al. 2022, §3), the walk
// alone in both forms, with the tets in the BVH's leaf order and in Hilbert order (Aman et al.
// 2022, §5), and direct volume rendering of the field with and without early ray
// termination.
#pragma once

#include <json/json.h>

#include "render/scene/camera.hpp"
#include "render/walk/volume_render.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct LayoutFigures {
  double build_ms = 0;
  double build_ms_per_mtet = 0;
  double bytes_per_tet = 0;  // the per-tet records and the boundary face list
  double walk_ms = 0;        // every pixel's ray walked, nothing done in the tets
  double mtets_per_s = 0;
};

struct WalkFigures {
  LayoutFigures tet20, tet16;                  // tets in the BVH's leaf order
  LayoutFigures tet20_hilbert, tet16_hilbert;  // the same tets in Hilbert order
  double hilbert_order_ms = 0;                 // sorting and renumbering
  std::size_t boundary_faces = 0;
  double boundary_build_ms = 0;
  double dvr_ms = 0;  // early termination at 0.99
  double dvr_mtets_per_s = 0;
  double dvr_full_ms = 0;  // no early termination
  double dvr_full_mtets_per_s = 0;
  double lost_rays = 0;
};

// The field's transfer function, ending rays at opacity `termination` (1: never).
render::VolumeRenderOptions dvr_options(double termination);

WalkFigures measure_walk(const GyroidTwist& scene, const render::Camera& camera);
void print_walk(const WalkFigures& figures);
Json::Value walk_json(const WalkFigures& figures);

}  // namespace tetray::bench
