#include "adaptor/step/thread_budget.hpp"

#include <sched.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

namespace tetray {
namespace {

std::optional<std::string> first_line(const std::string& path) {
  std::ifstream file(path);
  std::string line;
  if (!file || !std::getline(file, line)) return std::nullopt;
  return line;
}

// cgroup v2: "QUOTA PERIOD" in microseconds, or "max PERIOD" when unlimited.
std::optional<double> quota_v2(const std::string& dir) {
  const std::optional<std::string> line = first_line(dir + "/cpu.max");
  if (!line) return std::nullopt;
  std::istringstream fields(*line);
  std::string quota;
  double period = 0;
  if (!(fields >> quota >> period) || quota == "max" || period <= 0) return std::nullopt;
  try {
    return std::stod(quota) / period;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

// cgroup v1: cpu.cfs_quota_us (-1 when unlimited) over cpu.cfs_period_us.
std::optional<double> quota_v1(const std::string& dir) {
  const std::optional<std::string> quota = first_line(dir + "/cpu.cfs_quota_us");
  const std::optional<std::string> period = first_line(dir + "/cpu.cfs_period_us");
  if (!quota || !period) return std::nullopt;
  try {
    const double q = std::stod(*quota), p = std::stod(*period);
    if (q <= 0 || p <= 0) return std::nullopt;
    return q / p;
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

}  // namespace

int cpus_in_affinity_mask() {
  cpu_set_t mask;
  CPU_ZERO(&mask);
  if (sched_getaffinity(0, sizeof mask, &mask) != 0) return 1;
  return std::max(1, CPU_COUNT(&mask));
}

std::optional<double> cgroup_cpu_quota(const std::string& cgroup_dir) {
  if (std::optional<double> quota = quota_v2(cgroup_dir)) return quota;
  return quota_v1(cgroup_dir);
}

std::string own_cgroup_dir() {
  // v1 lines "N:controllers:/path" (the cpu controller's is wanted); the v2 line "0::/path",
  // which a hybrid system lists too, only where no v1 cpu controller is mounted.
  std::ifstream file("/proc/self/cgroup");
  std::string v2_dir = "/sys/fs/cgroup";
  for (std::string line; std::getline(file, line);) {
    const std::size_t first = line.find(':'), second = line.find(':', first + 1);
    if (first == std::string::npos || second == std::string::npos) continue;
    const std::string controllers = line.substr(first + 1, second - first - 1);
    const std::string path = line.substr(second + 1);
    if (controllers.empty()) v2_dir = "/sys/fs/cgroup" + path;
    std::istringstream names(controllers);
    for (std::string name; std::getline(names, name, ',');) {
      if (name == "cpu") return "/sys/fs/cgroup/" + controllers + path;
    }
  }
  return v2_dir;
}

int default_thread_count() {
  int threads = cpus_in_affinity_mask();
  if (const std::optional<double> quota = cgroup_cpu_quota(own_cgroup_dir())) {
    threads = std::min(threads, std::max(1, static_cast<int>(std::floor(*quota))));
  }
  return threads;
}

int writer_thread_share(int budget) { return std::max(1, budget / 2); }

}  // namespace tetray
