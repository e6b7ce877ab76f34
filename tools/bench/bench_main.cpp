// tetray-bench: the gyroid-twist benchmark of docs/architecture.md §6. Per size it
// measures tetray (build, trace, counts, refit) and, in the same run and the same oneTBB arena, the
// extract-then-trace reference (VTK contour + Embree), prints a table with the targets and
// optionally writes JSON.
#include <unistd.h>

#include <tbb/task_arena.h>

#include <cstdio>
#include <exception>
#include <string>

#include "bench_depth_compare.hpp"
#include "bench_dvr_study.hpp"
#include "bench_json.hpp"
#include "bench_lod.hpp"
#include "bench_machine.hpp"
#include "bench_options.hpp"
#include "bench_reference_embree.hpp"
#include "bench_reference_vtk.hpp"
#include "bench_refit.hpp"
#include "bench_table.hpp"
#include "bench_targets.hpp"
#include "bench_tetray.hpp"
#include "bench_timing.hpp"
#include "bench_volume.hpp"
#include "tools/bench_common/bench_scene.hpp"
#include "tools/bench_common/json_file.hpp"

namespace tetray::bench {
namespace {

std::size_t available_memory() {
  return static_cast<std::size_t>(sysconf(_SC_AVPHYS_PAGES)) *
         static_cast<std::size_t>(sysconf(_SC_PAGE_SIZE));
}

ReferenceFigures measure_reference(const GyroidTwist& scene, const render::Camera& camera,
                                   const render::Framebuffer& tetray_image, int threads) {
  const ContourRun contour = contour_with_vtk(scene.mesh, scene.field, kIsovalue);
  const EmbreeRun embree = trace_with_embree(contour.triangles, camera, threads);
  const DepthAgreement agreement = compare_depth(tetray_image.depth, embree.depth);
  ReferenceFigures ref;
  ref.contour_ms = contour.contour_ms;
  ref.triangles = contour.triangles.triangle_count();
  ref.embree_build_ms = embree.build_ms;
  ref.embree_trace_ms = embree.trace_ms;
  ref.embree_packets = embree.packets;
  ref.embree_same_depth = embree.same_depth;
  const EmbreeStepBuild step = step_build_with_embree(contour.triangles, camera, threads, embree);
  ref.embree_step_build_ms = step.build_ms;
  ref.embree_step_trace_ms = step.trace_ms;
  ref.embree_step_depth_differs = step.depth_differs;
  ref.depth_agree_fraction = agreement.agree_fraction;
  ref.depth_median_rel_diff = agreement.median_rel_diff;
  ref.in_turn = trace_in_turn(scene, contour.triangles, camera, threads, embree.packets);
  return ref;
}

SceneFigures measure_scene(int n, const BenchOptions& options) {
  const double cpu_start = process_cpu_seconds();
  const render::Stopwatch wall;
  const render::Camera camera = bench_camera(options.size_px);
  const GyroidTwist scene = make_gyroid_twist(n, 0.0);
  SceneFigures figures;
  figures.n = n;
  figures.tets = scene.mesh.tet_count();
  TetrayRun tetray = measure_tetray(scene, camera);
  figures.tetray = std::move(tetray.figures);
  figures.ref = measure_reference(scene, camera, tetray.image, options.threads);
  figures.refit =
      measure_refit(scene, camera, {options.steps, options.threads, figures.ref.embree_packets});
  figures.walk = measure_walk(scene, camera);
  if (n == options.sizes.front()) {
    figures.vtk_volume = measure_vtk_volume(scene, camera, options.threads);
  } else {
    figures.vtk_volume.skipped = kVtkVolumeFirstSizeOnly;
  }
  figures.volume = measure_volume(scene, camera, options.threads);
  figures.shading = measure_shading(scene, camera);
  figures.layers = measure_layers(scene, camera);
  figures.cap = measure_cap(scene, camera);
  figures.cpu_share = (process_cpu_seconds() - cpu_start) / (wall.ms() * 1e-3 * options.threads);
  figures.peak_rss_mib = peak_rss_mib();
  return figures;
}

// Whether size n fits the memory available now; if not, says so in the report.
bool fits(int n, BenchReport& report) {
  if (estimated_bytes(n) <= available_memory() / 10 * 8) return true;
  report.skipped.push_back("n = " + std::to_string(n) + " skipped: needs about " +
                           std::to_string(estimated_bytes(n) >> 20) + " MiB, " +
                           std::to_string(available_memory() >> 20) + " MiB available");
  print_note(report.skipped.back());
  return false;
}

BenchReport run_bench(const BenchOptions& options) {
  BenchReport report;
  report.machine = describe_machine();
  report.threads = options.threads;
  print_header(report.machine, options.threads, options.size_px);
  tbb::task_arena arena(options.threads);
  std::vector<LodRow> lod_rows;
  for (const int n : options.sizes) {
    if (!fits(n, report)) continue;
    if (!options.lod_study_path.empty()) {
      arena.execute([&] {
        const std::vector<LodRow> rows =
            measure_lod_study(n, bench_camera(options.size_px), options.threads);
        print_lod_rows(rows);
        lod_rows.insert(lod_rows.end(), rows.begin(), rows.end());
      });
      write_lod_csv(lod_rows, options.lod_study_path);  // after each size: a long study keeps
      continue;                                         // what it measured if cut short
    }
    arena.execute([&] { report.scenes.push_back(measure_scene(n, options)); });
    print_scene(report.scenes.back());
  }
  return report;
}

// The volume-rendering error study alone (bench_dvr_study.hpp), on the first size.
void study_volume_rendering(const BenchOptions& options) {
  tbb::task_arena arena(options.threads);
  DvrStudy study;
  arena.execute([&] {
    study =
        run_dvr_study(make_gyroid_twist(options.sizes.front(), 0.0), bench_camera(options.size_px));
  });
  print_dvr_study(study);
  write_dvr_study_csv(study, options.dvr_study_path);
}

// One block of figures alone, per size: the header, then measure(scene, camera) for each size in
// one arena, its JSON object (with "n") appended under `key`.
template <typename Measure>
void measure_each_size(const BenchOptions& options, const char* key, Measure&& measure) {
  tbb::task_arena arena(options.threads);
  print_header(describe_machine(), options.threads, options.size_px);
  Json::Value json;
  for (const int n : options.sizes) {
    arena.execute([&] {
      const GyroidTwist scene = make_gyroid_twist(n, 0.0);
      std::printf("\n== gyroid-twist n = %d: %zu tets ==\n", n, scene.mesh.tet_count());
      Json::Value size = measure(scene, bench_camera(options.size_px));
      size["n"] = n;
      json[key].append(size);
      std::fflush(stdout);
    });
  }
  if (!options.json_path.empty()) write_json_file(json, options.json_path);
}

// The volume-rendering figures alone (bench_volume.hpp), per size.
void measure_volume_only(const BenchOptions& options) {
  measure_each_size(options, "volume", [&](const GyroidTwist& scene, const render::Camera& camera) {
    const VolumeFigures figures = measure_volume(scene, camera, options.threads);
    print_volume(figures);
    return volume_json(figures);
  });
}

// The shading, transparency and cap figures alone, per size, with their targets: the quick run
// for work on one of these modalities.
void measure_modalities_only(const BenchOptions& options) {
  measure_each_size(
      options, "modalities", [](const GyroidTwist& scene, const render::Camera& camera) {
        const ShadingFigures shading = measure_shading(scene, camera);
        print_shading(shading);
        const LayerFigures layers = measure_layers(scene, camera);
        print_layers(layers);
        const CapFigures cap = measure_cap(scene, camera);
        print_cap(cap);
        Json::Value size;
        size["shading"] = shading_json(shading);
        size["layers"] = layers_json(layers);
        size["cap"] = cap_json(cap);
        std::printf("  targets\n");
        for (const TargetCheck& check : check_modality_targets(shading, layers, cap)) {
          print_target(check);
          size["targets"].append(target_json(check));
        }
        return size;
      });
}

}  // namespace
}  // namespace tetray::bench

int main(int argc, char** argv) {
  using namespace tetray::bench;
  int exit_code = -1;
  const BenchOptions options = parse_options(argc, argv, exit_code);
  if (exit_code >= 0) return exit_code;
  try {
    if (!options.dvr_study_path.empty()) {
      study_volume_rendering(options);
      return 0;
    }
    if (options.volume_only) {
      measure_volume_only(options);
      return 0;
    }
    if (options.modalities_only) {
      measure_modalities_only(options);
      return 0;
    }
    const BenchReport report = run_bench(options);
    if (!options.json_path.empty()) write_json(report, options.json_path);
    return 0;
  } catch (const std::exception& error) {
    std::fprintf(stderr, "tetray-bench: %s\n", error.what());
    return 1;
  }
}
