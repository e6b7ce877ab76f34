// The functions of trace.cpp and shadow_rays.cpp in a dispatch build: each calls the variant
// render/isa chose (cmake/TetrayIsa.cmake).
#include "render/trace/dispatch/trace_kernels.hpp"

namespace tetray::render {
namespace {

const TraceKernels& variant() { return isa::kernels<TraceKernels>(TETRAY_ISA_TABLES(trace)); }

}  // namespace

Framebuffer trace(const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                  std::span<const IsoSurface> surfaces, const TraceOptions& options,
                  TraceStats* stats) {
  return variant().trace_image(volume, bvh, camera, surfaces, options, stats);
}

void trace_into(Framebuffer& image, const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                std::span<const IsoSurface> surfaces, const TraceOptions& options,
                TraceStats* stats, std::vector<Framebuffer>* shadow_terms) {
  variant().trace_into_image(image, volume, bvh, camera, surfaces, options, stats, shadow_terms);
}

std::vector<std::uint8_t> trace_shadow_rays(const TetVolume& volume, const Bvh& bvh,
                                            const Camera& camera,
                                            std::span<const IsoSurface> surfaces,
                                            const TraceOptions& options,
                                            std::span<const float> depth) {
  return variant().shadow_rays(volume, bvh, camera, surfaces, options, depth);
}

void apply_shadows(Framebuffer& image, std::span<const Framebuffer> shadow_terms,
                   std::span<const std::uint8_t> occluded) {
  variant().remove_shadowed_light(image, shadow_terms, occluded);
}

const char* to_string(PacketSize packet) { return variant().packet_name(packet); }

TraceStats& TraceStats::operator+=(const TraceStats& o) { return (this->*variant().add_stats)(o); }

bool has_transparency(std::span<const IsoSurface> surfaces) {
  return variant().any_transparent(surfaces);
}

void trace_layers(LayerImage& image, const TetVolume& volume, const Bvh& bvh, const Camera& camera,
                  std::span<const IsoSurface> surfaces, const TraceOptions& options,
                  TraceStats* stats) {
  variant().trace_layered(image, volume, bvh, camera, surfaces, options, stats);
}

void layer_view_depths(const FragmentImage& layers, const Camera& camera, int layer,
                       std::span<float> depth) {
  variant().view_depths_of_layer(layers, camera, layer, depth);
}

void view_depths_of_distances(const Camera& camera, std::size_t first, std::span<float> depth) {
  variant().view_depths_of_rays(camera, first, depth);
}

}  // namespace tetray::render
