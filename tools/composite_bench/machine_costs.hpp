// What this machine (or the simulated platform) charges the compositor: point-to-point latency
// and bandwidth by ping-pong, and the CPU time per pixel of the compositor's kernels, which the
// model image injects at scale (model_image.hpp).
#pragma once

#include <mpi.h>

#include "tools/composite_bench/model_image.hpp"

namespace tetray::composite_bench {

struct MachineCosts {
  double latency_s = 0;      // one-way time of an 8-byte message between ranks 0 and 1
  double bandwidth_Bps = 0;  // of a 16 MiB message
  PixelCosts pixel;          // measured on rank 0 at the given size, or given
};

// Collective over `world` (ranks 0 and 1 measure, the others wait). The pixel costs are
// measured on rank 0's CPU (thread CPU time, best of three) at `size` squared and broadcast.
MachineCosts measure_machine(MPI_Comm world, int size);

// A barrier whose waiting ranks sleep instead of spinning on the cores of an oversubscribed
// machine (a plain barrier under the simulator, where nothing spins).
void sleeping_barrier(MPI_Comm comm);

}  // namespace tetray::composite_bench
