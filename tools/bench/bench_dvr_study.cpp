#include "bench_dvr_study.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>

#include "bench_timing.hpp"
#include "bench_walk.hpp"
#include "render/walk/volume_render.hpp"
#include "tools/bench_common/bench_scene.hpp"

namespace tetray::bench {
namespace {

// The finest compared step over the reference's.
constexpr int kReferenceRefinement = 16;

double mean_tet_edge(const BoxMesh& mesh) {
  const auto point = [&](std::int64_t p) {
    return render::Vec3d{mesh.points[3 * p], mesh.points[3 * p + 1], mesh.points[3 * p + 2]};
  };
  double sum = 0;
  for (std::size_t t = 0; t < mesh.tet_count(); ++t) {
    const std::int64_t* v = &mesh.tets[4 * t];
    for (int a = 0; a < 4; ++a) {
      for (int b = a + 1; b < 4; ++b) sum += length(point(v[a]) - point(v[b]));
    }
  }
  return sum / (6.0 * static_cast<double>(mesh.tet_count()));
}

// One frame of the scene volume-rendered with `sample_step` (0: the exact integral).
render::Framebuffer render_frame(const render::TetVolume& volume, const render::WalkStructure& walk,
                                 const render::Camera& camera, double sample_step) {
  render::VolumeRenderOptions options = dvr_options(1.0);
  options.sample_step = sample_step;
  render::VolumeFragmentImage fragments = render::render_volume(volume, walk, camera, options);
  return render::resolve(fragments);
}

std::string step_text(double edges) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", edges);
  return text;
}

}  // namespace

DvrStudy run_dvr_study(const GyroidTwist& scene, const render::Camera& camera, int halvings) {
  render::TetVolume volume;
  render::Bvh bvh;
  load_scene(scene, volume, bvh);
  const render::WalkStructure walk = render::build_walk_structure(volume);
  DvrStudy study;
  study.mean_edge = mean_tet_edge(scene.mesh);
  study.reference_step = std::ldexp(1.0, -halvings) / kReferenceRefinement;
  render::Framebuffer reference;
  study.reference_ms = time_ms([&] {
    reference = render_frame(volume, walk, camera, study.reference_step * study.mean_edge);
  });
  const auto measure = [&](const std::string& name, double sample_step) {
    render::Framebuffer image;
    DvrStudyRow row;
    row.step = name;
    row.ms =
        best_ms(kRepetitions, [&] { image = render_frame(volume, walk, camera, sample_step); });
    row.error = image_error(reference, image, camera);
    study.rows.push_back(row);
  };
  measure("exact", 0);
  for (int h = 0; h <= halvings; ++h) {
    const double edges = std::ldexp(1.0, -h);
    measure(step_text(edges), edges * study.mean_edge);
  }
  return study;
}

void write_dvr_study_csv(const DvrStudy& study, const std::string& path) {
  std::ofstream out(path);
  out << "step,ms,mean_error,max_error\n";
  char line[128];
  for (const DvrStudyRow& row : study.rows) {
    std::snprintf(line, sizeof line, "%s,%.4f,%.6e,%.6e\n", row.step.c_str(), row.ms,
                  row.error.color_mean, row.error.color_max);
    out << line;
  }
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path);
}

void print_dvr_study(const DvrStudy& study) {
  std::printf(
      "volume rendering error against time: mean tet edge %.4g, reference step %.6g edges "
      "(%.0f ms)\n",
      study.mean_edge, study.reference_step, study.reference_ms);
  std::printf("  %-8s %10s %12s %12s\n", "step", "ms", "mean error", "max error");
  for (const DvrStudyRow& row : study.rows) {
    std::printf("  %-8s %10.1f %12.3e %12.3e\n", row.step.c_str(), row.ms, row.error.color_mean,
                row.error.color_max);
  }
}

}  // namespace tetray::bench
