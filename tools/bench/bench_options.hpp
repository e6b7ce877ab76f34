// Command line of tetray-bench.
#pragma once

#include <string>
#include <vector>

namespace tetray::bench {

struct BenchOptions {
  std::vector<int> sizes{32, 56, 88, 133};  // gyroid-twist resolutions n (6 n^3 tets)
  int threads = 2;
  std::string json_path;       // empty: no JSON
  int size_px = 1024;          // square image
  int steps = 5;               // time steps t = 0, 0.1, ... for the refit figures
  std::string lod_study_path;  // non-empty: only the level-of-detail study, as CSV here
  std::string dvr_study_path;  // not empty: only the volume-rendering error study, to this CSV
  bool volume_only = false;    // only the volume-rendering figures (bench_volume.hpp) per size
  // Only the shading, transparency and cap figures per size, with their targets.
  bool modalities_only = false;
};

// Parses argv; on --help or an error prints the message and returns the exit code to leave
// with in `exit_code`, else leaves it untouched.
BenchOptions parse_options(int argc, char** argv, int& exit_code);

}  // namespace tetray::bench
