// refit_bvh in a dispatch build: calls the variant render/isa chose (cmake/TetrayIsa.cmake).
#include "render/bvh/dispatch/refit_kernels.hpp"

namespace tetray::render {

void refit_bvh(const TetVolume& volume, Bvh& bvh, bool geometry) {
  isa::kernels<RefitKernels>(TETRAY_ISA_TABLES(refit)).refit(volume, bvh, geometry);
}

}  // namespace tetray::render
