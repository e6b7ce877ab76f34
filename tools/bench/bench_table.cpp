#include "bench_table.hpp"

#include <cstdio>

#include "bench_reference_embree.hpp"
#include "bench_targets.hpp"
#include "bench_timing.hpp"

namespace tetray::bench {
namespace {

template <typename Count>
double mega(Count value) {
  return static_cast<double>(value) * 1e-6;
}

void print_tetray(const SceneFigures& s) {
  std::printf(
      "  BVH build      BIH %.1f ms, SAH %.1f ms; %zu nodes, %.1f B/tet (nodes, leaf lists, tet "
      "ids)\n",
      s.tetray.build_bih_ms, s.tetray.build_sah_ms, s.tetray.bvh_nodes, s.tetray.bvh_bytes_per_tet);
  std::printf("  memory         vertex store %.1f B/tet; peak RSS of the bench so far %.0f MiB\n",
              s.tetray.volume_bytes_per_tet, s.peak_rss_mib);
  std::printf("  trace  packet  %9s %8s | per frame (M): %8s %8s %8s %8s %8s %8s\n", "ms",
              "Mrays/s", "pkt-box", "ray-box", "isorange", "extract", "ray-iso", "culled");
  for (const PacketFigures& p : s.tetray.packets) {
    const render::TraceStats& c = p.counts;
    std::printf("         %-6s %9.1f %8.1f |                %8.3f %8.3f %8.3f %8.3f %8.3f %8.3f\n",
                render::to_string(p.packet), p.trace_ms, p.mrays_per_s, mega(c.packet_box_tests),
                mega(c.ray_box_tests), mega(c.isorange_tests), mega(c.isopolygon_extractions),
                mega(c.ray_isopolygon_tests), mega(c.frustum_culled_isopolygons));
  }
}

void print_reference(const ReferenceFigures& r) {
  std::printf(
      "  reference      VTK contour %.1f ms (%.2f M triangles), Embree build %.1f ms,"
      " trace %.1f ms (%s; packets and single rays %s)\n",
      r.contour_ms, mega(r.triangles), r.embree_build_ms, r.embree_trace_ms,
      embree_trace_mode(r.embree_packets),
      r.embree_same_depth ? "give the same depth image" : "DIFFER");
  std::printf(
      "  reference step Embree build of a new step (dynamic scene, low quality) %.1f ms, trace"
      " %.1f ms (%zu pixels of the depth image differ from the default build's)\n",
      r.embree_step_build_ms, r.embree_step_trace_ms, r.embree_step_depth_differs);
  std::printf("  depth check    %.4f%% of pixels agree on hit/miss, median rel diff %.2e\n",
              100 * r.depth_agree_fraction, r.depth_median_rel_diff);
  std::printf(
      "  trace in turn  tetray %.1f ms (%s), Embree %.1f ms: %.2fx (best of %d rounds, a frame "
      "of each per round)\n",
      r.in_turn.tetray_ms, render::to_string(render::TraceOptions{}.packet), r.in_turn.embree_ms,
      r.in_turn.tetray_ms / r.in_turn.embree_ms, r.in_turn.rounds);
}

void print_refit(const RefitFigures& r) {
  std::printf(
      "  update         field only %.2f ms (memcpy bound %.2f ms, %.1f MB);"
      " geometry+field %.2f ms (bound %.2f ms, %.1f MB); rebuild %.1f ms\n",
      r.field_only_ms, r.bound_field_only_ms, mega(r.bytes_field_only), r.geometry_ms,
      r.bound_geometry_ms, mega(r.bytes_geometry), r.rebuild_ms);
  std::printf(
      "  in-situ step   %.1f ms (update + trace 16x16), %.1f ms (update + trace %s, the default)"
      " vs reference %.1f ms (contour + Embree new-step build + trace of the same steps)\n",
      r.step_total_ms, r.step_total_default_ms, render::to_string(render::TraceOptions{}.packet),
      r.ref_step_total_ms);
  std::printf(
      "  policy         quality ratio after the steps %.3f; strong twist: %s (ratio %.2f)\n",
      r.quality_ratio_after_steps, r.strong_deformation_kind.c_str(), r.strong_deformation_ratio);
}

void print_targets(const SceneFigures& s) {
  std::printf(
      "  targets (2 threads; the fixed ones defined on n = %d%s, those against the reference per "
      "size%s)\n",
      kFixedTargetScene, s.n == kFixedTargetScene ? "" : ", shown for reference",
      s.n == reference_targets(s.n).n ? "" : ", the nearest shown for reference");
  for (const TargetCheck& check : check_targets(s)) print_target(check);
}

}  // namespace

void print_header(const MachineInfo& machine, int threads, int size_px) {
  std::printf("tetray-bench: %s, %u cores, %s kernels; %d threads; %dx%d pixels\n",
              machine.cpu_model.c_str(), machine.cores, machine.simd_target.c_str(), threads,
              size_px, size_px);
  std::printf("times are the best of %d runs after a warm-up\n", kRepetitions);
}

void print_scene(const SceneFigures& s) {
  std::printf("\n== gyroid-twist n = %d: %zu tets (the bench got %.0f%% of its threads' time) ==\n",
              s.n, s.tets, 100 * s.cpu_share);
  print_tetray(s);
  print_reference(s.ref);
  print_refit(s.refit);
  print_walk(s.walk);
  print_vtk_volume(s.vtk_volume);
  print_volume(s.volume);
  print_shading(s.shading);
  print_layers(s.layers);
  print_cap(s.cap);
  print_targets(s);
  std::fflush(stdout);
}

void print_note(const std::string& note) {
  std::printf("\nnote: %s\n", note.c_str());
  std::fflush(stdout);
}

}  // namespace tetray::bench
