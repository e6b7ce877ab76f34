#include "bench_walk.hpp"

#include <cstdio>

#include "bench_timing.hpp"
#include "render/update/volume_update.hpp"
#include "render/walk/hilbert_order.hpp"
#include "render/walk/tet_walk.hpp"
#include "render/walk/volume_render.hpp"
#include "tools/bench_common/bench_scene.hpp"

namespace tetray::bench {

// Dense: nowhere clear, faint below 0.2, rising to 4 per half unit at 1.5.
render::VolumeRenderOptions dvr_options(double termination) {
  render::VolumeRenderOptions options;
  options.transfer = {render::find_colormap("viridis"),
                      -1.5,
                      1.5,
                      {{-1.5, 0.05}, {0.2, 0.1}, {0.8, 2}, {1.5, 4}},
                      0.5};
  options.termination = termination;
  return options;
}

namespace {

template <typename Layout>
LayoutFigures measure_layout(const render::TetVolume& volume, const render::BoundaryFaces& boundary,
                             const render::Camera& camera) {
  LayoutFigures figures;
  render::FaceAdjacency<Layout> adjacency;
  figures.build_ms =
      best_ms(kRepetitions, [&] { adjacency = render::build_face_adjacency<Layout>(volume); });
  const double tets = static_cast<double>(volume.tets.size());
  figures.build_ms_per_mtet = figures.build_ms * 1e6 / tets;
  figures.bytes_per_tet = static_cast<double>(adjacency.bytes()) / tets;
  const render::CameraFrame frame = render::make_frame(camera);
  std::vector<render::Vec3d> directions;
  for (int j = 0; j < camera.height; ++j) {
    for (int i = 0; i < camera.width; ++i) {
      directions.push_back(render::pixel_direction(frame, camera, i, j));
    }
  }
  const render::WalkMesh<Layout> mesh{volume, adjacency, boundary};
  render::WalkCounters counters;
  figures.walk_ms = best_ms(kRepetitions, [&] {
    counters = render::walk_rays(mesh, camera.eye - volume.origin, directions);
  });
  figures.mtets_per_s = static_cast<double>(counters.tets_visited) / (figures.walk_ms * 1e3);
  return figures;
}

}  // namespace

WalkFigures measure_walk(const GyroidTwist& scene, const render::Camera& camera) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(scene, volume, bvh);
  WalkFigures figures;
  render::WalkStructure walk = render::build_walk_structure(volume);
  figures.boundary_faces = walk.boundary.faces.size();
  figures.boundary_build_ms = best_ms(kRepetitions, [&] {
    walk.boundary = render::build_boundary_faces(volume, walk.adjacency.boundary);
  });
  figures.tet20 = measure_layout<render::Tet20>(volume, walk.boundary, camera);
  figures.tet16 = measure_layout<render::Tet16>(volume, walk.boundary, camera);
  render::TetVolume hilbert;
  figures.hilbert_order_ms =
      best_ms(kRepetitions, [&] { hilbert = render::hilbert_ordered(volume); });
  const render::WalkStructure hilbert_walk = render::build_walk_structure(hilbert);
  figures.tet20_hilbert = measure_layout<render::Tet20>(hilbert, hilbert_walk.boundary, camera);
  figures.tet16_hilbert = measure_layout<render::Tet16>(hilbert, hilbert_walk.boundary, camera);
  for (const double termination : {0.99, 1.0}) {
    render::VolumeRenderStats stats;
    const double ms = best_ms(kRepetitions, [&] {
      render::render_volume(volume, walk, camera, dvr_options(termination), &stats);
    });
    const double rate = static_cast<double>(stats.tets_visited) / (ms * 1e3);
    (termination < 1 ? figures.dvr_ms : figures.dvr_full_ms) = ms;
    (termination < 1 ? figures.dvr_mtets_per_s : figures.dvr_full_mtets_per_s) = rate;
    figures.lost_rays = static_cast<double>(stats.lost_rays);
  }
  return figures;
}

void print_walk(const WalkFigures& f) {
  std::printf("walk: %zu boundary faces (BVH %.1f ms)\n", f.boundary_faces, f.boundary_build_ms);
  std::printf("  %-6s %12s %14s %12s %10s %12s\n", "layout", "build ms", "ms per 1M tets",
              "bytes/tet", "walk ms", "Mtets/s");
  const auto row = [](const char* name, const LayoutFigures& l) {
    std::printf("  %-6s %12.1f %14.1f %12.2f %10.1f %12.1f\n", name, l.build_ms,
                l.build_ms_per_mtet, l.bytes_per_tet, l.walk_ms, l.mtets_per_s);
  };
  row("Tet20", f.tet20);
  row("Tet16", f.tet16);
  std::printf("  in Hilbert order (sorting %.1f ms):\n", f.hilbert_order_ms);
  row("Tet20", f.tet20_hilbert);
  row("Tet16", f.tet16_hilbert);
  std::printf(
      "  volume rendering: %.1f ms (%.1f Mtets/s) with early termination at 0.99, "
      "%.1f ms (%.1f Mtets/s) without; %.0f rays lost\n",
      f.dvr_ms, f.dvr_mtets_per_s, f.dvr_full_ms, f.dvr_full_mtets_per_s, f.lost_rays);
}

Json::Value walk_json(const WalkFigures& f) {
  Json::Value json;
  const auto layout = [](const LayoutFigures& l) {
    Json::Value v;
    v["build_ms"] = l.build_ms;
    v["build_ms_per_mtet"] = l.build_ms_per_mtet;
    v["bytes_per_tet"] = l.bytes_per_tet;
    v["walk_ms"] = l.walk_ms;
    v["mtets_per_s"] = l.mtets_per_s;
    return v;
  };
  json["tet20"] = layout(f.tet20);
  json["tet16"] = layout(f.tet16);
  json["tet20_hilbert"] = layout(f.tet20_hilbert);
  json["tet16_hilbert"] = layout(f.tet16_hilbert);
  json["hilbert_order_ms"] = f.hilbert_order_ms;
  json["boundary_faces"] = static_cast<Json::UInt64>(f.boundary_faces);
  json["boundary_build_ms"] = f.boundary_build_ms;
  json["dvr_ms"] = f.dvr_ms;
  json["dvr_mtets_per_s"] = f.dvr_mtets_per_s;
  json["dvr_no_termination_ms"] = f.dvr_full_ms;
  json["dvr_no_termination_mtets_per_s"] = f.dvr_full_mtets_per_s;
  json["lost_rays"] = f.lost_rays;
  return json;
}

}  // namespace tetray::bench
