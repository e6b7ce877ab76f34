// The --json output: issue 3's shape plus issue 4's "refit" object per scene.
#pragma once

#include <string>

#include "bench_results.hpp"

namespace tetray::bench {

// Throws std::runtime_error when the file cannot be written.
void write_json(const BenchReport& report, const std::string& path);

}  // namespace tetray::bench
