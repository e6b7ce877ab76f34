#include "bench_lod.hpp"

#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "bench_reference_embree.hpp"
#include "bench_reference_vtk.hpp"
#include "bench_timing.hpp"
#include "render/bvh/node_planes.hpp"
#include "tools/bench_common/bench_scene.hpp"

namespace tetray::bench {
namespace {

// Embree's trace of the extracted triangles, freed before the sweep (the 14M-tet scene's
// triangles and Embree's scene would otherwise stay resident through it).
double embree_trace_ms(const GyroidTwist& scene, const render::Camera& camera, int threads) {
  const ContourRun contour = contour_with_vtk(scene.mesh, scene.field, kIsovalue);
  return trace_with_embree(contour.triangles, camera, threads).trace_ms;
}

}  // namespace

std::vector<float> lod_thresholds() { return {1, 2, 4, 8, 16, 32, 64}; }

std::vector<LodRow> measure_lod_study(int n, const render::Camera& camera, int threads) {
  const GyroidTwist scene = make_gyroid_twist(n, 0.0);
  const double embree_ms = embree_trace_ms(scene, camera, threads);
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(scene, volume, bvh);
  const render::IsoSurface surface = bench_surface();
  render::TraceOptions options;  // the default (level of detail traces its 32x32 packets)
  render::Framebuffer exact, image;
  const auto frame = [&](render::Framebuffer& into) {
    return time_ms([&] { render::trace_into(into, volume, bvh, camera, {&surface, 1}, options); });
  };
  frame(exact);
  const double exact_ms = best_of_ms(kRepetitions, [&] { return frame(exact); });
  std::vector<render::NodePlane> planes;
  const double planes_ms = best_of_ms(
      kRepetitions, [&] { return time_ms([&] { fit_node_planes(volume, bvh, planes); }); });
  std::vector<LodRow> rows;
  for (const float node_pixels : lod_thresholds()) {
    options.lod = {node_pixels, planes};
    frame(image);
    LodRow row{n, volume.tets.size(), node_pixels, 0, exact_ms, embree_ms, planes_ms, {}};
    row.frame_ms = best_of_ms(kRepetitions, [&] { return frame(image); });
    row.error = image_error(exact, image, camera);
    rows.push_back(row);
  }
  return rows;
}

void print_lod_rows(const std::vector<LodRow>& rows) {
  std::printf("  lod study     %9s %8s %9s %9s %9s %10s %9s %9s %9s\n", "tets", "px err",
              "frame ms", "/ exact", "/ Embree", "hit/miss", "depth med", "depth p99", "color");
  for (const LodRow& r : rows)
    std::printf("                %9zu %8.2f %9.2f %9.2f %9.2f %9.4f%% %9.3f %9.3f %9.5f\n", r.tets,
                r.node_pixels, r.frame_ms, r.frame_ms / r.exact_ms, r.frame_ms / r.embree_trace_ms,
                100 * r.error.hit_miss_fraction, r.error.depth_median_px, r.error.depth_p99_px,
                r.error.color_mean);
  if (!rows.empty())
    std::printf("                exact frame %.2f ms, Embree trace %.2f ms, node fit %.2f ms\n",
                rows.back().exact_ms, rows.back().embree_trace_ms, rows.back().planes_ms);
}

void write_lod_csv(const std::vector<LodRow>& rows, const std::string& path) {
  std::ofstream out(path);
  out << "n,tets,node_pixels,frame_ms,exact_ms,embree_trace_ms,node_fit_ms,hit_miss_fraction,"
         "depth_error_median_px,depth_error_p99_px,color_error_mean\n";
  for (const LodRow& r : rows)
    out << r.n << ',' << r.tets << ',' << r.node_pixels << ',' << r.frame_ms << ',' << r.exact_ms
        << ',' << r.embree_trace_ms << ',' << r.planes_ms << ',' << r.error.hit_miss_fraction << ','
        << r.error.depth_median_px << ',' << r.error.depth_p99_px << ',' << r.error.color_mean
        << '\n';
  out.flush();
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace tetray::bench
