// The table of one variant: compiled once per instruction set with bvh_refit.cpp.
#include "render/bvh/dispatch/refit_kernels.hpp"

extern "C" const tetray::render::RefitKernels TETRAY_ISA_TABLE(refit) = {
    &tetray::render::refit_bvh};
