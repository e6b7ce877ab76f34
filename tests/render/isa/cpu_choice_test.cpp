// The choice of a variant for a given CPU (render/isa/cpu_choice.hpp): a CPU without some part of
// x86-64-v2 gets no variant and a message naming exactly what it lacks and the build that runs
// there; every other CPU gets the best variant of its levels, or the one TETRAY_ISA names. The
// expected lines are written out here, and this CPU's features are checked against libgcc's own
// test of the whole x86-64-v2 level.
#include <gtest/gtest.h>

#include <algorithm>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "render/isa/isa.hpp"

namespace tetray {
namespace {

using render::isa::Choice;
using render::isa::CpuFeatures;
using render::isa::Isa;
using render::isa::V2Feature;

constexpr V2Feature kEveryV2Feature[] = {
    V2Feature::sse3,   V2Feature::ssse3,      V2Feature::sse4_1,   V2Feature::sse4_2,
    V2Feature::popcnt, V2Feature::cmpxchg16b, V2Feature::lahf_sahf};

CpuFeatures cpu_of_level(int level) {
  CpuFeatures cpu;
  if (level >= 2) cpu.v2.set();
  cpu.v3 = level >= 3;
  cpu.v4 = level >= 4;
  return cpu;
}

CpuFeatures without(CpuFeatures cpu, V2Feature feature) {
  cpu.v2.reset(static_cast<std::size_t>(feature));
  return cpu;
}

std::string lacks_line(const std::string& missing) {
  return "this CPU lacks " + missing +
         " (x86-64-v2), which tetray's kernels need: build tetray with "
         "-DTETRAY_SIMD_TARGET=portable to run on it";
}

TEST(CpuChoice, FeatureNamesAreTheVendorsSpellings) {
  const char* expected[] = {"SSE3",   "SSSE3",      "SSE4.1",   "SSE4.2",
                            "POPCNT", "CMPXCHG16B", "LAHF/SAHF"};
  ASSERT_EQ(std::size(kEveryV2Feature), render::isa::kV2FeatureCount);
  for (std::size_t f = 0; f < render::isa::kV2FeatureCount; ++f)
    EXPECT_STREQ(render::isa::to_string(kEveryV2Feature[f]), expected[f]);
}

// Even a CPU with the higher levels' flags: each level includes the one below.
TEST(CpuChoice, ACpuLackingOneV2FeatureGetsNoVariantAndANameForIt) {
  for (V2Feature feature : kEveryV2Feature) {
    for (int level : {2, 3, 4}) {
      const CpuFeatures cpu = without(cpu_of_level(level), feature);
      const Choice choice = render::isa::choose(cpu, "");
      const std::string name = render::isa::to_string(feature);
      EXPECT_FALSE(choice.isa) << name << ", level flags " << level;
      EXPECT_EQ(choice.note, lacks_line(name));
      for (Isa isa : render::isa::kIsas) EXPECT_FALSE(render::isa::supports(cpu, isa)) << name;
    }
  }
}

TEST(CpuChoice, TheMessageListsEveryMissingFeatureInOrder) {
  CpuFeatures cpu = cpu_of_level(2);
  cpu = without(without(cpu, V2Feature::popcnt), V2Feature::sse4_2);
  EXPECT_EQ(render::isa::choose(cpu, "").note, lacks_line("SSE4.2, POPCNT"));
  EXPECT_EQ(render::isa::choose(cpu_of_level(1), "").note,
            lacks_line("SSE3, SSSE3, SSE4.1, SSE4.2, POPCNT, CMPXCHG16B, LAHF/SAHF"));
}

// TETRAY_ISA cannot make a CPU without x86-64-v2 run a variant.
TEST(CpuChoice, TetrayIsaDoesNotOverrideTheRefusal) {
  const CpuFeatures cpu = without(cpu_of_level(4), V2Feature::sse4_2);
  for (const char* requested : {"sse4.2", "avx2", "avx512", "avx9"}) {
    const Choice choice = render::isa::choose(cpu, requested);
    EXPECT_FALSE(choice.isa) << requested;
    EXPECT_EQ(choice.note, lacks_line("SSE4.2")) << requested;
  }
}

// The build the message names must be one the CMake option takes (the option's list of values,
// passed in by tests/render/isa/CMakeLists.txt).
TEST(CpuChoice, TheSuggestedBuildIsAValueOfTheCmakeOption) {
  const std::string note = render::isa::choose(cpu_of_level(1), "").note;
  const std::string option = "-DTETRAY_SIMD_TARGET=";
  const std::size_t at = note.find(option);
  ASSERT_NE(at, std::string::npos) << note;
  const std::string value =
      note.substr(at + option.size(), note.find(' ', at) - at - option.size());
  std::vector<std::string> values;
  std::stringstream list(TETRAY_SIMD_TARGETS);
  for (std::string v; std::getline(list, v, ',');) values.push_back(v);
  EXPECT_NE(std::find(values.begin(), values.end(), value), values.end())
      << value << " is not one of " << TETRAY_SIMD_TARGETS;
  EXPECT_NE(value, "dispatch");  // the build that refused
}

TEST(CpuChoice, EachLevelGetsItsBestVariant) {
  const Isa best[] = {Isa::sse4_2, Isa::avx2, Isa::avx512};
  const char* note[] = {"sse4.2: the best this CPU supports", "avx2: the best this CPU supports",
                        "avx512: the best this CPU supports"};
  for (int level = 2; level <= 4; ++level) {
    const Choice choice = render::isa::choose(cpu_of_level(level), "");
    ASSERT_TRUE(choice.isa) << level;
    EXPECT_EQ(*choice.isa, best[level - 2]);
    EXPECT_EQ(choice.note, note[level - 2]);
    EXPECT_FALSE(choice.request_refused);
  }
  CpuFeatures v4_without_v3 = cpu_of_level(4);
  v4_without_v3.v3 = false;
  EXPECT_EQ(render::isa::choose(v4_without_v3, "").isa, Isa::sse4_2);
}

TEST(CpuChoice, TetrayIsaPicksASupportedVariantAndRefusesTheRest) {
  const Choice named = render::isa::choose(cpu_of_level(4), "sse4.2");
  EXPECT_EQ(named.isa, Isa::sse4_2);
  EXPECT_EQ(named.note, "sse4.2: set by TETRAY_ISA");
  EXPECT_FALSE(named.request_refused);

  const Choice lacking = render::isa::choose(cpu_of_level(3), "avx512");
  EXPECT_EQ(lacking.isa, Isa::avx2);
  EXPECT_EQ(lacking.note,
            "TETRAY_ISA=avx512 refused: this CPU lacks it; using avx2, the best this CPU supports");
  EXPECT_TRUE(lacking.request_refused);

  const Choice unknown = render::isa::choose(cpu_of_level(2), "AVX2");
  EXPECT_EQ(unknown.isa, Isa::sse4_2);
  EXPECT_EQ(unknown.note,
            "TETRAY_ISA=AVX2 refused: not one of sse4.2, avx2, avx512; using sse4.2, the best this "
            "CPU supports");
  EXPECT_TRUE(unknown.request_refused);
}

// This CPU's features, each read alone, against libgcc's test of the whole level; and a CPU that
// has the level runs the kernels.
TEST(CpuChoice, ThisCpusFeaturesAgreeWithTheLevelTest) {
  if (!render::isa::dispatched()) {
    EXPECT_EQ(render::isa::kernels_refusal(), "") << "a build without variants refuses nothing";
    return;
  }
#if defined(__GNUC__) && defined(__x86_64__)
  const CpuFeatures cpu = render::isa::this_cpu();
  const bool v2 = __builtin_cpu_supports("x86-64-v2");
  EXPECT_EQ(cpu.v2.all(), v2);
  EXPECT_EQ(render::isa::kernels_refusal().empty(), v2);
  EXPECT_EQ(cpu.v3, static_cast<bool>(__builtin_cpu_supports("x86-64-v3")));
  EXPECT_EQ(cpu.v4, static_cast<bool>(__builtin_cpu_supports("x86-64-v4")));
#endif
}

// What a kernel call does on this CPU: run a variant, or throw the refusal without running any
// (the dispatchers call kernel_variant() before reading a table). On a CPU without x86-64-v2 this
// runs under emulation (tetray_isa_choice_test_on_a_core2).
TEST(CpuChoice, AKernelCallRunsAVariantOrThrowsTheRefusal) {
  const std::string refusal = render::isa::kernels_refusal();
  if (refusal.empty()) {
    EXPECT_EQ(render::isa::kernel_variant(), render::isa::active());
    return;
  }
  try {
    render::isa::kernel_variant();
    ADD_FAILURE() << "no refusal from a CPU that " << refusal;
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(e.what(), refusal);
  }
  EXPECT_NE(refusal.find("(x86-64-v2)"), std::string::npos) << refusal;
  for (Isa isa : render::isa::kIsas) EXPECT_FALSE(render::isa::activate(isa));
}

}  // namespace
}  // namespace tetray
