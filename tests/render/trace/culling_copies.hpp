// Every copy of the frustum and straddle tests (render/trace/culling_kernels.hpp) the library
// holds: the baseline's, and in a dispatch build each instruction-set variant's, so that the
// tests of render/trace check the code each variant runs. A copy this CPU cannot run gets no
// test instance (the list is made where the tests are listed, on the machine that runs them).
#pragma once

#include <gtest/gtest.h>

#include <ostream>
#include <string>
#include <vector>

#include "render/trace/culling_kernels.hpp"

namespace tetray::test {

struct CullingCopy {
  std::string name;  // "baseline", or the variant's: "sse4_2", "avx2", "avx512"
  const render::CullingKernels* kernels = nullptr;
};

std::vector<CullingCopy> culling_copies();

// How GoogleTest names a copy in a failure's message.
inline void PrintTo(const CullingCopy& copy, std::ostream* out) { *out << copy.name; }

// A test suite run once per copy: kernels() is the copy under test.
class CullingCopies : public ::testing::TestWithParam<CullingCopy> {
 protected:
  const render::CullingKernels& kernels() const { return *GetParam().kernels; }
};

std::string copy_name(const ::testing::TestParamInfo<CullingCopy>& info);

}  // namespace tetray::test

// Runs the TEST_Ps of `suite` (a subclass of CullingCopies) once per copy.
#define TETRAY_FOR_EACH_CULLING_COPY(suite)                                                      \
  INSTANTIATE_TEST_SUITE_P(Copies, suite, ::testing::ValuesIn(::tetray::test::culling_copies()), \
                           ::tetray::test::copy_name)
