// The choice of a kernel variant as a pure function of what a CPU offers and of TETRAY_ISA, so
// that a test can hand it any CPU, one without x86-64-v2 included; render/isa/isa.cpp calls it
// once per process with this CPU's features (docs/building.md, "Instruction sets").
#pragma once

#include <array>
#include <bitset>
#include <optional>
#include <string>
#include <string_view>

namespace tetray::render::isa {

// The x86-64 micro-architecture levels of the variants: x86-64-v2 (SSE4.2), x86-64-v3 (AVX2,
// FMA, BMI) and x86-64-v4 (AVX-512 F, BW, CD, DQ, VL), in increasing order.
enum class Isa { sse4_2, avx2, avx512 };
inline constexpr std::array kIsas = {Isa::sse4_2, Isa::avx2, Isa::avx512};

// "sse4.2", "avx2", "avx512": the names TETRAY_ISA takes.
const char* to_string(Isa isa);
std::optional<Isa> parse(std::string_view name);

// The instructions x86-64-v2 adds to baseline x86-64. The lowest variant is compiled for
// x86-64-v2 and may use any of them; everything outside the variants is baseline x86-64.
enum class V2Feature { sse3, ssse3, sse4_1, sse4_2, popcnt, cmpxchg16b, lahf_sahf };
inline constexpr std::size_t kV2FeatureCount = 7;

// "SSE3", "SSSE3", "SSE4.1", "SSE4.2", "POPCNT", "CMPXCHG16B", "LAHF/SAHF".
const char* to_string(V2Feature feature);

// A CPU as the choice sees it: which x86-64-v2 instructions it has, and whether it has all of
// x86-64-v3 and of x86-64-v4 (registers saved by the operating system included).
struct CpuFeatures {
  std::bitset<kV2FeatureCount> v2;  // bit f: the CPU has V2Feature f
  bool v3 = false;
  bool v4 = false;
};

// Whether a CPU can run the variant: it has the variant's level and every level below.
bool supports(const CpuFeatures& cpu, Isa isa);

// The variant a process runs, and the line that says why. No variant (`isa` empty) on a CPU
// without all of x86-64-v2: `note` then names what it lacks and how to build for it.
struct Choice {
  std::optional<Isa> isa;
  std::string note;
  bool request_refused = false;  // TETRAY_ISA named one this CPU lacks, or none at all
};

// The variant for a CPU and the value of TETRAY_ISA (empty: unset): the one it names, else the
// best the CPU supports.
Choice choose(const CpuFeatures& cpu, std::string_view requested);

}  // namespace tetray::render::isa
