// The instruction sets the hot kernels are compiled for in a dispatch build, and the choice of
// one at run time (docs/architecture.md §7): the best the CPU supports, or the one TETRAY_ISA
// names. Native and portable builds compile the kernels once; there the choice is fixed.
#pragma once

#include <array>
#include <cstddef>
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

// Whether the CPU (and the operating system) can run the variant; false in a build without
// variants.
bool cpu_supports(Isa isa);

// True in a dispatch build (TETRAY_SIMD_TARGET=dispatch), where the kernels exist per Isa.
bool dispatched();

// The variant the kernels run with. Chosen on first use: the one TETRAY_ISA names, or the best
// the CPU supports when it is unset or names one the CPU lacks (see choice_note()). A build
// without variants has none: there it is Isa::sse4_2 and names nothing (check dispatched()).
Isa active();

// Makes `isa` the active variant from now on (tests, benchmarks); false and no change when the
// build is not a dispatch build or the CPU lacks it.
bool activate(Isa isa);

// One line for the log: the variant and why it was chosen ("avx512: the best this CPU
// supports"), or the build's fixed target.
std::string choice_note();

// The kernels of one library per variant, in kIsas order: `tables[k]` is compiled for kIsas[k].
template <typename Kernels>
const Kernels& kernels(const std::array<const Kernels*, kIsas.size()>& tables) {
  return *tables[static_cast<std::size_t>(active())];
}

}  // namespace tetray::render::isa

// The name of the one symbol a variant's objects export (cmake/TetrayIsa.cmake localizes every
// other): tetrayisa_<kernels>_<isa>, e.g. tetrayisa_trace_avx2.
#define TETRAY_ISA_TABLE_NAME(kernels, isa) tetrayisa_##kernels##_##isa
#define TETRAY_ISA_TABLE_OF(kernels, isa) TETRAY_ISA_TABLE_NAME(kernels, isa)
// In a variant's table source: its own table (TETRAY_ISA is set per variant by the build).
#define TETRAY_ISA_TABLE(kernels) TETRAY_ISA_TABLE_OF(kernels, TETRAY_ISA)
// In a dispatcher: the tables of every variant, in kIsas order.
#define TETRAY_ISA_TABLES(kernels)                                                  \
  {                                                                                 \
    &TETRAY_ISA_TABLE_NAME(kernels, sse4_2), &TETRAY_ISA_TABLE_NAME(kernels, avx2), \
        &TETRAY_ISA_TABLE_NAME(kernels, avx512)                                     \
  }
