// What the figures were measured on: CPU model, cores, and the SIMD level the kernels were
// compiled for.
#pragma once

#include "bench_results.hpp"

namespace tetray::bench {

MachineInfo describe_machine();

// User + system CPU time of this process so far.
double process_cpu_seconds();

// The largest resident memory of this process so far, in MiB.
double peak_rss_mib();

}  // namespace tetray::bench
