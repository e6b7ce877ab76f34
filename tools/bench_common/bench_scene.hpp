// The gyroid-twist benchmark scene of docs/architecture.md §6 as the bench uses it: mesh and field
// at a time step, the camera, the isosurface, and the views the renderer ingests.
#pragma once

#include <cstddef>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/scene/camera.hpp"
#include "render/trace/trace.hpp"
#include "render/update/volume_update.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

inline constexpr double kTimeStep = 0.1;  // t = 0, 0.1, 0.2, ...
inline constexpr float kIsovalue = 0.0f;

render::Camera bench_camera(int size_px);
render::IsoSurface bench_surface();

render::PointSource point_source(const std::vector<double>& points);
render::FieldSource field_source(const std::vector<double>& field);

// Loads the mesh and field into a fresh volume and builds its BVH with `policy`.
render::UpdateResult load_scene(const GyroidTwist& scene, render::TetVolume& volume,
                                render::Bvh& bvh, const render::UpdatePolicy& policy = {});

// One frame of the scene's isosurface into `image`, whose storage is reused from frame to
// frame as in situ; statistics are collected only when `stats` is given.
void trace_scene(const render::TetVolume& volume, const render::Bvh& bvh,
                 const render::Camera& camera, render::PacketSize packet,
                 render::Framebuffer& image, render::TraceStats* stats = nullptr);

// A deformation far beyond the benchmark's steps: a full turn of twist about z from the bottom
// of the cube to the top, which stretches every tet's bounds and should make the policy rebuild.
std::vector<double> strong_twist(const BoxMesh& reference);

// Rough peak memory of one scene's run, to skip sizes that cannot fit.
std::size_t estimated_bytes(int n);

}  // namespace tetray::bench
