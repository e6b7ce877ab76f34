// The figures tetray-bench measures, one record per scene; the table printer, the JSON writer
// and the target checks all read these, so every figure has exactly one name.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "bench_cap.hpp"
#include "bench_layers.hpp"
#include "bench_shading.hpp"
#include "bench_trace_in_turn.hpp"
#include "bench_volume.hpp"
#include "bench_vtk_volume.hpp"
#include "bench_walk.hpp"
#include "render/trace/trace.hpp"

namespace tetray::bench {

// The JSON objects per packet size are keyed by render::to_string(packet).

struct PacketFigures {
  render::PacketSize packet = render::PacketSize::p16x16;
  double trace_ms = 0;
  double mrays_per_s = 0;
  render::TraceStats counts{};  // one frame, from a separate run with statistics on
};

struct TetrayFigures {
  double build_bih_ms = 0;
  double build_sah_ms = 0;
  double bvh_bytes_per_tet = 0;     // BVH nodes + tet id array, per tet
  double volume_bytes_per_tet = 0;  // the vertex store: vertices, tets, point map, per tet
  std::size_t bvh_nodes = 0;
  std::vector<PacketFigures> packets;  // in render::kPacketSizes order
};

struct ReferenceFigures {
  double contour_ms = 0;
  std::size_t triangles = 0;
  double embree_build_ms = 0;
  double embree_trace_ms = 0;
  bool embree_packets = false;  // the faster of Embree's traces is the packet one, not single rays
  bool embree_same_depth = false;   // its packet and single-ray traces gave the same depth image
  double embree_step_build_ms = 0;  // a new step's build (EmbreeBuild::new_step), the step's
  double embree_step_trace_ms = 0;  // and its trace
  std::size_t embree_step_depth_differs = 0;  // pixels where it is not the static scene's
  double depth_agree_fraction = 0;
  double depth_median_rel_diff = 0;
  TraceInTurn in_turn;  // tetray's exact trace and Embree's, alternating: the trace targets
};

// A new time step on the same topology. The bounds are memcpy times of the bytes each
// update must touch (bench_bandwidth.hpp says which).
struct RefitFigures {
  double field_only_ms = 0;
  double geometry_ms = 0;
  std::size_t bytes_field_only = 0;
  std::size_t bytes_geometry = 0;
  double bound_field_only_ms = 0;
  double bound_geometry_ms = 0;
  double rebuild_ms = 0;
  // update (geometry + field) + trace, each step the best of a few runs, median over steps:
  double step_total_ms = 0;          // traced in 16x16 packets, the step's packet size
  double step_total_default_ms = 0;  // in the default packets (render::TraceOptions)
  double ref_step_total_ms = 0;
  double quality_ratio_after_steps = 0;
  std::string strong_deformation_kind;  // the policy's decision after a strong twist
  double strong_deformation_ratio = 0;
};

struct SceneFigures {
  int n = 0;
  std::size_t tets = 0;
  // CPU time the process used / (wall time x threads) while measuring this scene: well below 1
  // means other processes held the cores and the absolute times are inflated (ratios less so).
  double cpu_share = 0;
  double peak_rss_mib = 0;  // the process's peak resident memory once this scene was measured
  TetrayFigures tetray;
  ReferenceFigures ref;
  RefitFigures refit;
  WalkFigures walk;
  VtkVolumeFigures vtk_volume;  // measured at the run's first size only
  VolumeFigures volume;
  ShadingFigures shading;
  LayerFigures layers;
  CapFigures cap;

  const PacketFigures& packet(render::PacketSize size) const;
};

struct MachineInfo {
  std::string cpu_model;
  unsigned cores = 0;
  std::string simd_target;
};

struct BenchReport {
  MachineInfo machine;
  int threads = 0;
  std::vector<SceneFigures> scenes;
  std::vector<std::string> skipped;  // one note per size that was not run
};

}  // namespace tetray::bench
