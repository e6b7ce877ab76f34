#include "bench_machine.hpp"

#include <sys/resource.h>

#include <fstream>
#include <string>
#include <thread>

#include "render/isa/isa.hpp"

namespace tetray::bench {
namespace {

std::string cpu_model() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  const std::string key = "model name";
  for (std::string line; std::getline(cpuinfo, line);)
    if (line.starts_with(key)) {
      const auto colon = line.find(':');
      if (colon != std::string::npos) return line.substr(line.find_first_not_of(' ', colon + 1));
    }
  return "unknown";
}

// A dispatch build names the variant it runs; otherwise the bench is compiled with the same
// flags as the renderer (TETRAY_SIMD_TARGET), so its predefined macros name the instruction set
// the kernels use.
std::string simd_target() {
  if (render::isa::dispatched() && !render::isa::kernels_refusal().empty())
    return "no (dispatch: this CPU lacks x86-64-v2)";
  if (render::isa::dispatched())
    return std::string(render::isa::to_string(render::isa::active())) + " (dispatch)";
#if defined(__AVX512F__)
  return "avx512";
#elif defined(__AVX2__)
  return "avx2";
#elif defined(__AVX__)
  return "avx";
#elif defined(__SSE4_2__)
  return "sse4.2";
#elif defined(__SSE2__)
  return "sse2";
#else
  return "scalar";
#endif
}

}  // namespace

MachineInfo describe_machine() {
  return {cpu_model(), std::thread::hardware_concurrency(), simd_target()};
}

double process_cpu_seconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) {
    return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec);
  };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

double peak_rss_mib() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // ru_maxrss is in KiB on Linux
}

}  // namespace tetray::bench
