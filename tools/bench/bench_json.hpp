// The --json output: per scene the build, trace and reference figures and a "refit" object.
#pragma once

#include <string>

#include "bench_results.hpp"

namespace tetray::bench {

// Throws std::runtime_error when the file cannot be written.
void write_json(const BenchReport& report, const std::string& path);

}  // namespace tetray::bench
