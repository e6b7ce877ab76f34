// How many threads a rank's renderer may use. Left to itself, oneTBB sizes its pool from the
// machine, so 128 ranks bound one per core on a 128-core node would each start 128 threads. The
// default here is the CPUs of the process's affinity mask (what mpirun's binding leaves it),
// capped by the CPU quota of its cgroup (a container's or a batch job's limit), and at least 1.
#pragma once

#include <optional>
#include <string>

namespace tetray {

// The CPUs the process may run on (sched_getaffinity); 1 if the mask cannot be read.
int cpus_in_affinity_mask();

// The CPU quota in CPUs of the cgroup whose files are under `cgroup_dir` (cgroup v2 `cpu.max`,
// or v1 `cpu.cfs_quota_us` / `cpu.cfs_period_us`); none when unlimited or unreadable.
std::optional<double> cgroup_cpu_quota(const std::string& cgroup_dir);

// The cgroup directory of this process (from /proc/self/cgroup, under /sys/fs/cgroup).
std::string own_cgroup_dir();

// min(affinity CPUs, floor(quota)), at least 1.
int default_thread_count();

// The writer's threads (output.writer_threads unset) out of a rank's `budget`: half of it, at
// least 1. The writer encodes while the solver computes its next steps, and its arena yields
// oneTBB's workers to the renderer during a render step (adaptor/output/image_writer.hpp).
int writer_thread_share(int budget);

}  // namespace tetray
