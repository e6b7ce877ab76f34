#include "bench_json.hpp"

#include <stdexcept>

#include "bench_targets.hpp"
#include "tools/bench_common/json_file.hpp"

namespace tetray::bench {
namespace {

Json::Value counts(const render::TraceStats& stats) {
  Json::Value json;
  json["rays"] = count(stats.rays);
  json["hits"] = count(stats.hits);
  json["packet_box_tests"] = count(stats.packet_box_tests);
  json["ray_box_tests"] = count(stats.ray_box_tests);
  json["isorange_tests"] = count(stats.isorange_tests);
  json["isopolygon_extractions"] = count(stats.isopolygon_extractions);
  json["ray_isopolygon_tests"] = count(stats.ray_isopolygon_tests);
  json["frustum_culled_isopolygons"] = count(stats.frustum_culled_isopolygons);
  return json;
}

Json::Value reference(const ReferenceFigures& ref) {
  Json::Value json;
  json["contour_ms"] = number(ref.contour_ms);
  json["triangles"] = count(ref.triangles);
  json["embree_build_ms"] = number(ref.embree_build_ms);
  json["embree_trace_ms"] = number(ref.embree_trace_ms);
  json["embree_packets"] = ref.embree_packets;
  json["embree_same_depth"] = ref.embree_same_depth;
  json["embree_step_build_ms"] = number(ref.embree_step_build_ms);
  json["embree_step_trace_ms"] = number(ref.embree_step_trace_ms);
  json["embree_step_depth_differs"] = count(ref.embree_step_depth_differs);
  json["depth_agree_fraction"] = number(ref.depth_agree_fraction);
  json["depth_median_rel_diff"] = number(ref.depth_median_rel_diff);
  json["trace_in_turn"]["rounds"] = ref.in_turn.rounds;
  json["trace_in_turn"]["tetray_ms"] = number(ref.in_turn.tetray_ms);
  json["trace_in_turn"]["embree_ms"] = number(ref.in_turn.embree_ms);
  return json;
}

Json::Value refit(const RefitFigures& refit) {
  Json::Value json;
  json["field_only_ms"] = number(refit.field_only_ms);
  json["geometry_ms"] = number(refit.geometry_ms);
  json["bound_field_only_ms"] = number(refit.bound_field_only_ms);
  json["bound_geometry_ms"] = number(refit.bound_geometry_ms);
  json["rebuild_ms"] = number(refit.rebuild_ms);
  json["step_total_ms"] = number(refit.step_total_ms);
  json["step_total_default_packet_ms"] = number(refit.step_total_default_ms);
  json["ref_step_total_ms"] = number(refit.ref_step_total_ms);
  json["quality_ratio_after_steps"] = number(refit.quality_ratio_after_steps);
  json["strong_deformation"]["kind"] = refit.strong_deformation_kind;
  json["strong_deformation"]["quality_ratio"] = number(refit.strong_deformation_ratio);
  return json;
}

Json::Value scene(const SceneFigures& figures) {
  Json::Value json;
  json["n"] = figures.n;
  json["tets"] = count(figures.tets);
  json["cpu_share"] = number(figures.cpu_share);
  json["build_bih_ms"] = number(figures.tetray.build_bih_ms);
  json["build_sah_ms"] = number(figures.tetray.build_sah_ms);
  json["bvh_bytes_per_tet"] = number(figures.tetray.bvh_bytes_per_tet);
  json["volume_bytes_per_tet"] = number(figures.tetray.volume_bytes_per_tet);
  json["peak_rss_mib"] = number(figures.peak_rss_mib);
  json["bvh_nodes"] = count(figures.tetray.bvh_nodes);
  for (const PacketFigures& packet : figures.tetray.packets) {
    const char* label = render::to_string(packet.packet);
    json["trace_ms"][label] = number(packet.trace_ms);
    json["mrays_per_s"][label] = number(packet.mrays_per_s);
    json["counts"][label] = counts(packet.counts);
  }
  json["ref"] = reference(figures.ref);
  json["refit"] = refit(figures.refit);
  json["walk"] = walk_json(figures.walk);
  json["walk"]["vtk_volume"] = vtk_volume_json(figures.vtk_volume);
  json["volume"] = volume_json(figures.volume);
  json["shading"] = shading_json(figures.shading);
  json["layers"] = layers_json(figures.layers);
  json["cap"] = cap_json(figures.cap);
  for (const TargetCheck& check : check_targets(figures))
    json["targets"].append(target_json(check));
  return json;
}

Json::Value report_json(const BenchReport& report) {
  Json::Value json;
  json["machine"]["cpu_model"] = report.machine.cpu_model;
  json["machine"]["cores"] = report.machine.cores;
  json["machine"]["simd_target"] = report.machine.simd_target;
  json["threads"] = report.threads;
  json["scenes"] = Json::Value(Json::arrayValue);
  for (const SceneFigures& figures : report.scenes) json["scenes"].append(scene(figures));
  json["skipped"] = Json::Value(Json::arrayValue);
  for (const std::string& note : report.skipped) json["skipped"].append(note);
  return json;
}

}  // namespace

void write_json(const BenchReport& report, const std::string& path) {
  if (!write_json_file(report_json(report), path)) {
    throw std::runtime_error("cannot write " + path);
  }
}

}  // namespace tetray::bench
