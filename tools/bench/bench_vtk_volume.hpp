// The volume-rendering peer: VTK 9.1's unstructured-grid volume rendering of the same field,
// transfer function, camera and black background as tetray's walk (bench_walk.hpp), offscreen in
// an X window (Xvfb with Mesa's llvmpipe where there is no GPU), each configuration's render time
// and its per-pixel RGB difference from tetray's image. VTK's transfer function is given at every
// breakpoint of tetray's (color in linear RGB, opacity o with the same unit distance, which VTK's
// linear integrator reads as the extinction o / unit_distance, as tetray does).
#pragma once

#include <json/json.h>

#include <string>
#include <vector>

#include "bench_dvr_study.hpp"
#include "render/scene/camera.hpp"
#include "scenes/box_mesh.hpp"

namespace tetray::bench {

struct VtkVolumeRun {
  std::string mapper;     // the mapper and its ray integrator
  double first_ms = 0;    // the first render, with the mapper's set-up
  double render_ms = 0;   // best of kRepetitions renders after it
  ImageError difference;  // RGB against tetray's image, VTK's read back as 8 bits
};

// VtkVolumeFigures::skipped at the sizes after the first.
inline constexpr const char* kVtkVolumeFirstSizeOnly = "measured at the first size only";

struct VtkVolumeFigures {
  std::string skipped;   // why nothing was measured; empty when measured
  double tetray_ms = 0;  // tetray's frame without early termination, as VTK's
  std::vector<VtkVolumeRun> runs;
};

VtkVolumeFigures measure_vtk_volume(const GyroidTwist& scene, const render::Camera& camera,
                                    int threads);
void print_vtk_volume(const VtkVolumeFigures& figures);
Json::Value vtk_volume_json(const VtkVolumeFigures& figures);

}  // namespace tetray::bench
