// The table of the trace library's instruction-set variants (cmake/TetrayIsa.cmake): every
// function trace.cpp and shadow_rays.cpp define, as the dispatch build compiles those files only
// per variant (trace_dispatch.cpp defines them for the rest of the program), and the variant's
// copy of the frustum and straddle tests for the tests.
#pragma once

#include "render/isa/isa.hpp"
#include "render/trace/culling_kernels.hpp"
#include "render/trace/shadow_rays.hpp"
#include "render/trace/trace.hpp"

namespace tetray::render {

struct TraceKernels {
  decltype(&trace) trace_image;
  decltype(&trace_into) trace_into_image;
  decltype(&trace_shadow_rays) shadow_rays;
  decltype(&apply_shadows) remove_shadowed_light;
  const char* (*packet_name)(PacketSize);
  decltype(&TraceStats::operator+=) add_stats;
  decltype(&has_transparency) any_transparent;
  decltype(&trace_layers) trace_layered;
  decltype(&layer_view_depths) view_depths_of_layer;
  decltype(&view_depths_of_distances) view_depths_of_rays;
  // Not called by the dispatch: the variant's own copy of the frustum and straddle tests, for the
  // tests of render/trace (culling_kernels.hpp).
  const CullingKernels* culling;
};

}  // namespace tetray::render

extern "C" const tetray::render::TraceKernels TETRAY_ISA_TABLE_NAME(trace, sse4_2),
    TETRAY_ISA_TABLE_NAME(trace, avx2), TETRAY_ISA_TABLE_NAME(trace, avx512);
