#include "render/isa/cpu_choice.hpp"

namespace tetray::render::isa {
namespace {

bool has_all_of_v2(const CpuFeatures& cpu) { return cpu.v2.all(); }

std::optional<Isa> best_supported(const CpuFeatures& cpu) {
  std::optional<Isa> best;
  for (Isa isa : kIsas)
    if (supports(cpu, isa)) best = isa;
  return best;
}

// Names what the CPU lacks of x86-64-v2 and the build that runs there: a portable build compiles
// the kernels for baseline x86-64 too.
std::string lacking_message(const CpuFeatures& cpu) {
  std::string missing;
  for (std::size_t f = 0; f < kV2FeatureCount; ++f) {
    if (cpu.v2[f]) continue;
    if (!missing.empty()) missing += ", ";
    missing += to_string(static_cast<V2Feature>(f));
  }
  return "this CPU lacks " + missing +
         " (x86-64-v2), which tetray's kernels need: build tetray with "
         "-DTETRAY_SIMD_TARGET=portable to run on it";
}

}  // namespace

const char* to_string(Isa isa) {
  switch (isa) {
    case Isa::sse4_2:
      return "sse4.2";
    case Isa::avx2:
      return "avx2";
    case Isa::avx512:
      return "avx512";
  }
  return "?";
}

std::optional<Isa> parse(std::string_view name) {
  for (Isa isa : kIsas)
    if (name == to_string(isa)) return isa;
  return std::nullopt;
}

const char* to_string(V2Feature feature) {
  switch (feature) {
    case V2Feature::sse3:
      return "SSE3";
    case V2Feature::ssse3:
      return "SSSE3";
    case V2Feature::sse4_1:
      return "SSE4.1";
    case V2Feature::sse4_2:
      return "SSE4.2";
    case V2Feature::popcnt:
      return "POPCNT";
    case V2Feature::cmpxchg16b:
      return "CMPXCHG16B";
    case V2Feature::lahf_sahf:
      return "LAHF/SAHF";
  }
  return "?";
}

bool supports(const CpuFeatures& cpu, Isa isa) {
  switch (isa) {
    case Isa::sse4_2:
      return has_all_of_v2(cpu);
    case Isa::avx2:
      return has_all_of_v2(cpu) && cpu.v3;
    case Isa::avx512:
      return has_all_of_v2(cpu) && cpu.v3 && cpu.v4;
  }
  return false;
}

Choice choose(const CpuFeatures& cpu, std::string_view requested) {
  const std::optional<Isa> best = best_supported(cpu);
  if (!best) return {std::nullopt, lacking_message(cpu)};
  const std::string best_name = to_string(*best);
  if (requested.empty()) return {best, best_name + ": the best this CPU supports"};
  const std::string refused = "TETRAY_ISA=" + std::string(requested) + " refused: ";
  const std::string fallback = "; using " + best_name + ", the best this CPU supports";
  const std::optional<Isa> named = parse(requested);
  if (!named) return {best, refused + "not one of sse4.2, avx2, avx512" + fallback, true};
  if (!supports(cpu, *named)) return {best, refused + "this CPU lacks it" + fallback, true};
  return {named, std::string(to_string(*named)) + ": set by TETRAY_ISA"};
}

}  // namespace tetray::render::isa
