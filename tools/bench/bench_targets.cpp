#include "bench_targets.hpp"

#include <cstdio>
#include <cstdlib>
#include <utility>

namespace tetray::bench {
namespace {

// printf-style formatting into a string (GCC 12 has no std::format).
std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

// Tetray's dense frame against the VTK mapper named `mapper` (how many times faster), with the
// target `at_least`; a row saying why when VTK was not measured.
TargetCheck against_vtk(const VtkVolumeFigures& vtk, const std::string& mapper, double at_least) {
  const std::string name = "dense volume vs VTK " + mapper;
  const std::string target = format(">= %.0fx faster", at_least);
  for (const VtkVolumeRun& run : vtk.runs) {
    if (run.mapper != mapper) continue;
    const double speedup = run.render_ms / vtk.tetray_ms;
    return {name, format("%.2fx faster", speedup), target, speedup >= at_least};
  }
  return {name, "not measured: " + vtk.skipped, target, false};
}

}  // namespace

void print_target(const TargetCheck& check) {
  std::printf("    %-34s %-20s %-14s %s\n", check.name.c_str(), check.measured.c_str(),
              check.target.c_str(), check.pass ? "PASS" : "MISS");
}

Json::Value target_json(const TargetCheck& check) {
  Json::Value target;
  target["name"] = check.name;
  target["measured"] = check.measured;
  target["target"] = check.target;
  target["pass"] = check.pass;
  return target;
}

const ReferenceTargets& reference_targets(int n) {
  const ReferenceTargets* nearest = &kReferenceTargets[0];
  for (const ReferenceTargets& t : kReferenceTargets)
    if (std::abs(t.n - n) < std::abs(nearest->n - n)) nearest = &t;
  return *nearest;
}

std::vector<TargetCheck> check_targets(const SceneFigures& s) {
  const double trace16_ms = s.packet(render::PacketSize::p16x16).trace_ms;
  const double mrays = s.packet(render::PacketSize::p16x16).mrays_per_s;
  const double vs_embree = trace16_ms / s.ref.embree_trace_ms;
  const double bih_mtets_per_s = static_cast<double>(s.tets) / (s.tetray.build_bih_ms * 1e3);
  const double sah_vs_bih = s.tetray.build_sah_ms / s.tetray.build_bih_ms;
  const double geometry_vs_bound = s.refit.geometry_ms / s.refit.bound_geometry_ms;
  const double field_vs_bound = s.refit.field_only_ms / s.refit.bound_field_only_ms;
  const ReferenceTargets& sized = reference_targets(s.n);
  const double default_vs_embree = s.ref.in_turn.tetray_ms / s.ref.in_turn.embree_ms;
  const double default_step_speedup = s.refit.ref_step_total_ms / s.refit.step_total_default_ms;
  const bool rebuilt = s.refit.strong_deformation_kind == "rebuild";
  const double shells_vs_iso = s.volume.shells.ms / s.volume.iso_ms;
  std::vector<TargetCheck> checks = {
      {"trace 16x16", format("%.1f Mrays/s", mrays), ">= 40 Mrays/s", mrays >= 40},
      {"trace 16x16 / Embree trace", format("%.2fx", vs_embree), "<= 1.5x", vs_embree <= 1.5},
      {"BIH build", format("%.1f M tets/s", bih_mtets_per_s), ">= 20 M tets/s",
       bih_mtets_per_s >= 20},
      {"SAH build / BIH build", format("%.2fx", sah_vs_bih), "<= 5x", sah_vs_bih <= 5},
      {"BVH memory", format("%.1f B/tet", s.tetray.bvh_bytes_per_tet), "< 20 B/tet",
       s.tetray.bvh_bytes_per_tet < 20},
      {"hit/miss agreement", format("%.4f%%", 100 * s.ref.depth_agree_fraction), ">= 99.9%",
       s.ref.depth_agree_fraction >= 0.999},
      {"median rel depth diff", format("%.2e", s.ref.depth_median_rel_diff), "< 1e-5",
       s.ref.depth_median_rel_diff < 1e-5},
      {"Embree new-step build, depth",
       format("%.0f px differ", static_cast<double>(s.ref.embree_step_depth_differs)),
       "0 (the default's)", s.ref.embree_step_depth_differs == 0},
      {"geometry+field refit / bound", format("%.2fx", geometry_vs_bound), "<= 2x",
       geometry_vs_bound <= 2},
      {"field-only refit / bound", format("%.2fx", field_vs_bound), "<= 1.5x",
       field_vs_bound <= 1.5},
      {format("exact trace / Embree (n = %.0f)", sized.n), format("%.2fx", default_vs_embree),
       format("<= %.1fx", sized.trace_vs_embree), default_vs_embree <= sized.trace_vs_embree},
      {format("reference / in-situ step (n = %.0f)", sized.n),
       format("%.1fx faster", default_step_speedup), format(">= %.0fx faster", sized.step_speedup),
       default_step_speedup >= sized.step_speedup},
      {"quality ratio after steps", format("%.3f", s.refit.quality_ratio_after_steps), "< 1.2",
       s.refit.quality_ratio_after_steps < 1.2},
      {"strong deformation",
       s.refit.strong_deformation_kind + format(" (ratio %.2f)", s.refit.strong_deformation_ratio),
       "rebuild", rebuilt},
      {"volume shells / isosurfaces", format("%.2fx", shells_vs_iso), "<= 3x", shells_vs_iso <= 3},
  };
  // VTK's mappers run at the first size only: the other sizes have no such rows.
  if (s.vtk_volume.skipped != kVtkVolumeFirstSizeOnly) {
    checks.push_back(against_vtk(s.vtk_volume, "projected tetrahedra (OpenGL)", 2));
    checks.push_back(against_vtk(s.vtk_volume, "ray cast, linear integrator", 10));
  }
  for (TargetCheck& check : check_modality_targets(s.shading, s.layers, s.cap))
    checks.push_back(std::move(check));
  return checks;
}

std::vector<TargetCheck> check_modality_targets(const ShadingFigures& shading,
                                                const LayerFigures& layers, const CapFigures& cap) {
  const auto at_most = [](const char* name, double ratio, double target) {
    return TargetCheck{name, format("%.2fx", ratio), format("<= %.1fx", target), ratio <= target};
  };
  return {
      at_most("shadowing point light / plain", shading.shadow_ms / shading.plain_ms, 2),
      at_most("4 layers / the same surfaces opaque", layers.transparent_ms / layers.opaque_pair_ms,
              2),
      at_most("smooth step / flat step", smooth_step_ratio(shading), 1.5),
      at_most("clip cap / plain", cap.cap_ms / cap.plain_ms, 2),
  };
}

}  // namespace tetray::bench
