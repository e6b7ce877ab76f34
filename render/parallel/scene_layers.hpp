// Transparent surfaces of one scene across ranks (Wald et al. 2007, §8.5, made exact for a split
// mesh): every rank peels its nearest layers per pixel (render/trace/trace.hpp, trace_layers),
// and each pixel keeps its nearest max_layers of all ranks together
// (render/composite/fragment_composite.hpp) — the layers one rank tracing the whole mesh keeps.
// Without shadows the ranks merge and blend them in stripes of the image; with shadowing lights
// the fragment compositor gathers them onto the writer, and each kept layer's hit point is
// shadowed as a first hit is (scene_shadows.hpp): the writer shares layer l's depths, every rank
// traces their shadow rays against its tets, the occlusion is ORed onto the writer, which removes
// each occluded light's part of that layer's color before blending.
#pragma once

#include <mpi.h>

#include <vector>

#include "render/composite/fragment_composite.hpp"
#include "render/core/framebuffer.hpp"
#include "render/parallel/protocol_status.hpp"
#include "render/parallel/scene_shadows.hpp"
#include "render/trace/trace.hpp"

namespace tetray::render {

// The writer's merged layers of a view (with shadows), or the compositor's buffers of this
// rank's stripe (without), kept by the caller from frame to frame so that their storage is
// reused (a fresh image of fragments each frame cost its page faults).
struct MergedLayers {
  FragmentImage color;
  std::vector<FragmentImage> shadow_terms;
  FragmentWorkspace<Fragment> stripes;
};

// Collective over `comm`. `local` is this rank's layers (trace_layers with scene.options). On
// return the writer's `image` is the blended image, with the first layer's view depth and key;
// `kept` holds the writer's merged layers (with shadowing lights) or this rank's stripe
// buffers. A rank alone in `comm` blends its own layers where
// they are, with no gather: `local` is then left with each pixel's fragments in depth order and
// its shadowed colors. A rank whose shadow rays failed (memory) still takes part in every
// collective, with no occlusion, and returns a local error afterwards.
ProtocolStatus composite_layers(LayerImage& local, const ShadowScene& scene, int writer,
                                MPI_Comm comm, Framebuffer& image, MergedLayers& kept);

}  // namespace tetray::render
