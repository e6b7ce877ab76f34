// The instruction sets the hot kernels are compiled for in a dispatch build, and the choice of
// one at run time (docs/architecture.md §7): the best the CPU supports, or the one TETRAY_ISA
// names. Native and portable builds compile the kernels once; there the choice is fixed.
#pragma once

#include <array>
#include <cstddef>
#include <string>

#include "render/isa/cpu_choice.hpp"

namespace tetray::render::isa {

// This CPU's features, from __builtin_cpu_supports; none in a build without variants.
CpuFeatures this_cpu();

// Whether this CPU (and the operating system) can run the variant; false in a build without
// variants.
bool cpu_supports(Isa isa);

// Why this CPU cannot run the kernels of a dispatch build (it lacks part of x86-64-v2), naming
// what it lacks; empty where it can, and in a build without variants. Adaptor creation returns it
// as its error, before anything else.
std::string kernels_refusal();

// True in a dispatch build (TETRAY_SIMD_TARGET=dispatch), where the kernels exist per Isa.
bool dispatched();

// The variant the kernels run with. Chosen on first use: the one TETRAY_ISA names, or the best
// the CPU supports when it is unset or names one the CPU lacks (see choice_note()). A build
// without variants, or a CPU without one, has none: there it is Isa::sse4_2 and names nothing
// (check dispatched() and kernels_refusal()).
Isa active();

// The variant a kernel call runs: active(), or a std::runtime_error with kernels_refusal() on a
// CPU that runs no variant, where no variant's code may ever run (it would fault).
Isa kernel_variant();

// Makes `isa` the active variant from now on (tests, benchmarks); false and no change when the
// build is not a dispatch build or the CPU lacks it.
bool activate(Isa isa);

// One line for the log: the variant and why it was chosen ("avx512: the best this CPU
// supports"), the refusal on a CPU that runs none, or the build's fixed target.
std::string choice_note();

// The kernels of one library per variant, in kIsas order: `tables[k]` is compiled for kIsas[k].
template <typename Kernels>
const Kernels& kernels(const std::array<const Kernels*, kIsas.size()>& tables) {
  return *tables[static_cast<std::size_t>(kernel_variant())];
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
