#include "culling_copies.hpp"

#include <algorithm>
#include <array>

#if TETRAY_DISPATCH
#include "render/trace/dispatch/trace_kernels.hpp"
#endif

namespace tetray::test {

std::vector<CullingCopy> culling_copies() {
  std::vector<CullingCopy> copies = {{"baseline", &render::kCullingKernels}};
#if TETRAY_DISPATCH
  // The tables are data: reading a variant's does not run its code.
  const std::array<const render::TraceKernels*, render::isa::kIsas.size()> tables =
      TETRAY_ISA_TABLES(trace);
  for (std::size_t k = 0; k < tables.size(); ++k) {
    const render::isa::Isa isa = render::isa::kIsas[k];
    if (!render::isa::cpu_supports(isa)) continue;  // no test instance rather than a skipped one
    std::string name = render::isa::to_string(isa);
    std::replace(name.begin(), name.end(), '.', '_');  // a test name's characters
    copies.push_back({name, tables[k]->culling});
  }
#endif
  return copies;
}

std::string copy_name(const ::testing::TestParamInfo<CullingCopy>& info) { return info.param.name; }

}  // namespace tetray::test
