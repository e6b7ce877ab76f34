// The human-readable output of tetray-bench: one block per scene, then its targets.
#pragma once

#include "bench_results.hpp"

namespace tetray::bench {

void print_header(const MachineInfo& machine, int threads, int size_px);
void print_scene(const SceneFigures& figures);
void print_note(const std::string& note);

}  // namespace tetray::bench
