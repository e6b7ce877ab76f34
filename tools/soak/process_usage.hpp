// What a long run watches for leaks, read from Linux's /proc/self: resident memory now (VmRSS)
// and at its peak (VmHWM), and the number of open file descriptors.
#pragma once

#include <cstddef>
#include <cstdint>

namespace tetray::tools {

struct ProcessUsage {
  std::uint64_t rss_kb = 0;
  std::uint64_t peak_rss_kb = 0;
  std::size_t open_fds = 0;  // entries of /proc/self/fd, the one listing them included
};

ProcessUsage process_usage();

}  // namespace tetray::tools
