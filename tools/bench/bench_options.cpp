#include "bench_options.hpp"

#include <CLI/CLI.hpp>

namespace tetray::bench {

BenchOptions parse_options(int argc, char** argv, int& exit_code) {
  BenchOptions options;
  CLI::App app{"tetray-bench: gyroid-twist benchmark of tetray against VTK contour + Embree"};
  app.add_option("--sizes", options.sizes, "gyroid-twist resolutions n, comma-separated")
      ->delimiter(',')
      ->check(CLI::Range(1, 1000));
  app.add_option("--threads", options.threads, "threads (one oneTBB arena for everything)")
      ->check(CLI::Range(1, 1024));
  app.add_option("--json", options.json_path, "write the figures as JSON to this file");
  app.add_option("--size-px", options.size_px, "image width and height in pixels")
      ->check(CLI::Range(1, 16384));
  app.add_option("--steps", options.steps, "time steps t = 0, 0.1, ... for the refit figures")
      ->check(CLI::Range(1, 100));
  app.add_option("--lod-study", options.lod_study_path,
                 "run only the level-of-detail study for the sizes and write it as CSV here");
  app.add_option("--dvr-study", options.dvr_study_path,
                 "only run the volume-rendering error-against-time study on the first size, "
                 "writing its CSV here");
  app.add_flag("--volume-only", options.volume_only,
               "only the volume-rendering figures of each size (shells, dense, skipping)");
  app.add_flag("--modalities-only", options.modalities_only,
               "only the shadow, clip, smooth-shading, transparency and cap figures of each size, "
               "with their targets");
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& error) {
    exit_code = app.exit(error) == 0 ? 0 : 1;  // README: 1 on a usage error, 0 for --help
  }
  return options;
}

}  // namespace tetray::bench
