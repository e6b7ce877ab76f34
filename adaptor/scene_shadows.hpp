// Shadows of one scene across ranks (Wald et al. 2007, §7; render/composite/shadow_visibility.hpp):
// after its image is composited onto the writer rank, the writer's depth goes to every rank,
// each traces the shadow rays of those hit points against its own tets, the occlusion bits are
// ORed onto the writer, and the writer removes the occluded lights' terms. The same code runs
// on one rank without MPI traffic, so every rank count gives the image of one rank.
#pragma once

#include <span>
#include <vector>

#include "collective.hpp"
#include "render/bvh/bvh.hpp"
#include "render/core/framebuffer.hpp"
#include "render/trace/camera.hpp"
#include "render/trace/trace.hpp"
#include "render/volume/tet_volume.hpp"
#include "tetray/adaptor.hpp"

namespace tetray {

struct ShadowScene {
  const render::TetVolume& volume;
  const render::Bvh& bvh;
  const render::Camera& camera;
  std::span<const render::IsoSurface> surfaces;
  const render::TraceOptions& options;  // its lights and clip region
};

// Collective over `comm`. `image` is the scene's image, already composited onto `writer`;
// `terms` this rank's shadow terms (trace_into), composited here. On return the writer's image
// is shaded with shadows. A rank whose shadow rays failed (memory) still takes part in every
// collective, with no occlusion, and returns its error afterwards.
Status shadow_scene(render::Framebuffer& image, std::vector<render::Framebuffer>& terms,
                    const ShadowScene& scene, const Communicator& comm, int writer);

}  // namespace tetray
