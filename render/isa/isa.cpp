#include "render/isa/isa.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>

namespace tetray::render::isa {
namespace {

Choice initial_choice() {
  if (!dispatched()) {
    const std::string target = TETRAY_SIMD_TARGET_NAME;
    return {Isa::sse4_2, target + " build: one variant (TETRAY_ISA needs a dispatch build)"};
  }
  const char* requested = std::getenv("TETRAY_ISA");
  return choose(this_cpu(), requested != nullptr ? requested : "");
}

// A refused TETRAY_ISA is also reported on stderr, by every process that reads it: each may run
// on a different CPU.
const Choice& choice() {
  static const Choice c = [] {
    Choice initial = initial_choice();
    if (initial.request_refused) std::fprintf(stderr, "tetray: %s\n", initial.note.c_str());
    return initial;
  }();
  return c;
}

// The active variant, read on every kernel call: choice() fixes the first, activate() may
// change it while no kernel runs.
std::atomic<Isa>& active_isa() {
  static std::atomic<Isa> a{choice().isa.value_or(Isa::sse4_2)};
  return a;
}

}  // namespace

CpuFeatures this_cpu() {
  CpuFeatures cpu;
#if TETRAY_DISPATCH
  // Each feature alone, to name the missing ones (__builtin_cpu_supports takes only literals);
  // the higher levels whole, as their variants' -march=x86-64-vN may use any of their
  // instructions (the checks include the operating system's saving of the AVX and AVX-512
  // registers).
  __builtin_cpu_init();  // also when called before libgcc's own initialiser
  const auto set = [&](V2Feature f, int present) {
    cpu.v2[static_cast<std::size_t>(f)] = present != 0;
  };
  set(V2Feature::sse3, __builtin_cpu_supports("sse3"));
  set(V2Feature::ssse3, __builtin_cpu_supports("ssse3"));
  set(V2Feature::sse4_1, __builtin_cpu_supports("sse4.1"));
  set(V2Feature::sse4_2, __builtin_cpu_supports("sse4.2"));
  set(V2Feature::popcnt, __builtin_cpu_supports("popcnt"));
  set(V2Feature::cmpxchg16b, __builtin_cpu_supports("cmpxchg16b"));
  set(V2Feature::lahf_sahf, __builtin_cpu_supports("lahf_lm"));
  cpu.v3 = __builtin_cpu_supports("x86-64-v3");
  cpu.v4 = __builtin_cpu_supports("x86-64-v4");
#endif
  return cpu;
}

bool cpu_supports(Isa isa) { return dispatched() && supports(this_cpu(), isa); }

std::string kernels_refusal() {
  if (!dispatched() || choice().isa) return "";
  return choice().note;
}

bool dispatched() { return TETRAY_DISPATCH != 0; }

Isa active() { return active_isa().load(std::memory_order_relaxed); }

Isa kernel_variant() {
  if (dispatched() && !choice().isa) throw std::runtime_error(choice().note);
  return active();
}

bool activate(Isa isa) {
  if (!cpu_supports(isa)) return false;
  active_isa().store(isa, std::memory_order_relaxed);
  return true;
}

std::string choice_note() {
  if (!dispatched() || !choice().isa) return choice().note;
  const Isa now = active();
  if (now == choice().isa) return choice().note;
  return std::string(to_string(now)) + ": set by the program";
}

}  // namespace tetray::render::isa
