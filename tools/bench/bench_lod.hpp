// tetray-bench --lod-study: the level of detail's image error against render time. Per size, the
// exact frame, Embree's trace of the extracted triangles (the reference of the same run), and a
// sweep of the LOD threshold: frame ms, the per-step node fit, and the image error against the
// exact frame. Written as CSV (one row per size and threshold) and printed as a table.
#pragma once

#include <string>
#include <vector>

#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"
#include "tools/bench_common/image_error.hpp"

namespace tetray::bench {

struct LodRow {
  int n = 0;
  std::size_t tets = 0;
  float node_pixels = 0;
  double frame_ms = 0, exact_ms = 0, embree_trace_ms = 0, planes_ms = 0;
  ImageError error;
};

// The thresholds swept, in pixel footprints.
std::vector<float> lod_thresholds();

std::vector<LodRow> measure_lod_study(int n, const render::Camera& camera, int threads);
void print_lod_rows(const std::vector<LodRow>& rows);
// Throws std::runtime_error naming the file when it cannot be written.
void write_lod_csv(const std::vector<LodRow>& rows, const std::string& path);

}  // namespace tetray::bench
