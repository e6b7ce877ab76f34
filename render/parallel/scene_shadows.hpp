// Shadows of one scene across ranks (Wald et al. 2007, §7; shadow_visibility.hpp): after its
// image is composited onto the writer rank, the writer's depth goes to every rank, each traces
// the shadow rays of those hit points against its own tets, the occlusion bits are ORed onto the
// writer, and the writer removes the occluded lights' terms. The same code runs on one rank
// without MPI traffic, so every rank count gives the image of one rank.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/core/framebuffer.hpp"
#include "render/parallel/protocol_status.hpp"
#include "render/scene/camera.hpp"
#include "render/scene/iso_surface.hpp"
#include "render/scene/trace_options.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// What a rank traces its shadow rays against: its own tets, with the scene's camera, surfaces
// and options (their lights and clip region).
struct ShadowScene {
  const TetVolume& volume;
  const Bvh& bvh;
  const Camera& camera;
  std::span<const IsoSurface> surfaces;
  const TraceOptions& options;
};

// Collective over `comm`. `image` is the scene's image, already composited onto `writer`;
// `terms` this rank's shadow terms (trace_into), composited here. On return the writer's image
// is shaded with shadows, and `occluded`, when given, holds the writer's combined occlusion
// bits (trace_shadow_rays' per pixel). A rank whose shadow rays failed (memory) still takes part
// in every collective, with no occlusion, and returns a local error afterwards.
ProtocolStatus shadow_across_ranks(Framebuffer& image, std::vector<Framebuffer>& terms,
                                   const ShadowScene& scene, int writer, MPI_Comm comm,
                                   std::vector<std::uint8_t>* occluded = nullptr);

}  // namespace tetray::render
