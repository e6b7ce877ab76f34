#include "tools/soak/process_usage.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace tetray::tools {

ProcessUsage process_usage() {
  ProcessUsage usage;
  {
    std::ifstream status("/proc/self/status");  // closed before the descriptors are counted
    for (std::string line; std::getline(status, line);) {
      std::istringstream fields(line);
      std::string key;
      fields >> key;
      if (key == "VmRSS:") fields >> usage.rss_kb;
      if (key == "VmHWM:") fields >> usage.peak_rss_kb;
    }
  }
  std::error_code ec;
  for (std::filesystem::directory_iterator fd("/proc/self/fd", ec), end; !ec && fd != end;
       fd.increment(ec)) {
    ++usage.open_fds;
  }
  return usage;
}

}  // namespace tetray::tools
