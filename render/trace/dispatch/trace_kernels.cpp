// The table of one variant: compiled once per instruction set with the trace library's sources.
#include "render/trace/dispatch/trace_kernels.hpp"

namespace tetray::render {

extern "C" const TraceKernels TETRAY_ISA_TABLE(trace) = {&trace,
                                                         &trace_into,
                                                         &trace_shadow_rays,
                                                         &apply_shadows,
                                                         &to_string,
                                                         &TraceStats::operator+=,
                                                         &has_transparency,
                                                         &trace_layers,
                                                         &layer_view_depths,
                                                         &view_depths_of_distances,
                                                         &kCullingKernels};

}  // namespace tetray::render
