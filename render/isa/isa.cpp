#include "render/isa/isa.hpp"

#include <atomic>
#include <cstdio>
#include <cstdlib>

namespace tetray::render::isa {
namespace {

struct Choice {
  Isa isa;
  std::string note;
  bool refused = false;  // TETRAY_ISA named one this build or CPU cannot run
};

// The best variant the CPU supports. The lowest is taken on a CPU without x86-64-v2 too: a
// dispatch build needs SSE4.2 (README.md, "Instruction sets").
Isa best_supported() {
  Isa best = Isa::sse4_2;
  for (Isa isa : kIsas)
    if (cpu_supports(isa)) best = isa;
  return best;
}

Choice initial_choice() {
  if (!dispatched()) {
    const std::string target = TETRAY_SIMD_TARGET_NAME;
    return {Isa::sse4_2, target + " build: one variant (TETRAY_ISA needs a dispatch build)"};
  }
  const Isa best = best_supported();
  const char* requested = std::getenv("TETRAY_ISA");
  if (requested == nullptr || *requested == '\0')
    return {best, std::string(to_string(best)) + ": the best this CPU supports"};
  const std::optional<Isa> named = parse(requested);
  const std::string fallback =
      std::string("; using ") + to_string(best) + ", the best this CPU supports";
  if (!named) {
    return {best,
            std::string("TETRAY_ISA=") + requested + " refused: not one of sse4.2, avx2, avx512" +
                fallback,
            true};
  }
  if (!cpu_supports(*named))
    return {best, std::string("TETRAY_ISA=") + requested + " refused: this CPU lacks it" + fallback,
            true};
  return {*named, std::string(to_string(*named)) + ": set by TETRAY_ISA"};
}

// A refused TETRAY_ISA is also reported on stderr, by every process that reads it: each may run
// on a different CPU.
Choice& choice() {
  static Choice c = [] {
    Choice initial = initial_choice();
    if (initial.refused) std::fprintf(stderr, "tetray: %s\n", initial.note.c_str());
    return initial;
  }();
  return c;
}

// The active variant, read on every kernel call: choice() fixes the first, activate() may
// change it while no kernel runs.
std::atomic<Isa>& active_isa() {
  static std::atomic<Isa> a{choice().isa};
  return a;
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

bool cpu_supports(Isa isa) {
#if TETRAY_DISPATCH
  // The whole level, as the variant's -march=x86-64-vN may use any of its instructions; the
  // check includes the operating system's saving of the AVX and AVX-512 registers.
  switch (isa) {
    case Isa::sse4_2:
      return __builtin_cpu_supports("x86-64-v2");
    case Isa::avx2:
      return __builtin_cpu_supports("x86-64-v3");
    case Isa::avx512:
      return __builtin_cpu_supports("x86-64-v4");
  }
#endif
  (void)isa;
  return false;
}

bool dispatched() { return TETRAY_DISPATCH != 0; }

Isa active() { return active_isa().load(std::memory_order_relaxed); }

bool activate(Isa isa) {
  if (!dispatched() || !cpu_supports(isa)) return false;
  active_isa().store(isa, std::memory_order_relaxed);
  return true;
}

std::string choice_note() {
  if (!dispatched()) return choice().note;
  const Isa now = active();
  if (now == choice().isa) return choice().note;
  return std::string(to_string(now)) + ": set by the program";
}

}  // namespace tetray::render::isa
