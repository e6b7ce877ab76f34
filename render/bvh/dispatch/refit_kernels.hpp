// The table of the refit's instruction-set variants (cmake/TetrayIsa.cmake): the function
// bvh_refit.cpp defines, which the dispatch build compiles only per variant.
#pragma once

#include "render/bvh/bvh.hpp"
#include "render/isa/isa.hpp"

namespace tetray::render {

struct RefitKernels {
  decltype(&refit_bvh) refit;
};

}  // namespace tetray::render

extern "C" const tetray::render::RefitKernels TETRAY_ISA_TABLE_NAME(refit, sse4_2),
    TETRAY_ISA_TABLE_NAME(refit, avx2), TETRAY_ISA_TABLE_NAME(refit, avx512);
