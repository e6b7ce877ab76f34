// Shadow rays (Wald et al. 2007, §7): from each hit point of a composited image towards each
// shadowing light, any-hit with early out, through the one traversal (packet_traversal.hpp) and
// leaf operation (leaf_intersect.hpp). Rays towards a point light share its position as their
// origin, so they travel as packets from the light to the hit points, culled by the interval
// test of the traversal (Wald et al. 2007, §5.2 III: no corner rays); rays towards a directional
// light share no origin and travel one by one.
//
// The hit points come from the image's depth alone, so every rank, given the same composited
// depth, traces the same rays against its own tets, and "occluded" is a logical OR over the ranks
// (render/parallel/shadow_visibility.hpp): the image is the same for any rank count.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/core/framebuffer.hpp"
#include "render/scene/camera.hpp"
#include "render/trace/trace.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// Per pixel of `depth` (the composited image's, row-major; +infinity where nothing was hit), bit
// j set when a surface of `surfaces` in `volume` (within options.clip) lies between the hit
// point and shadowing light j of options.lights (in their order). At most 8 shadowing lights.
std::vector<std::uint8_t> trace_shadow_rays(const TetVolume& volume, const Bvh& bvh,
                                            const Camera& camera,
                                            std::span<const IsoSurface> surfaces,
                                            const TraceOptions& options,
                                            std::span<const float> depth);

// Whether a shadowing light's term (premultiplied RGBA) gives its pixel or layer any color: where
// none does, removing the terms changes nothing, occluded or not.
inline bool term_has_color(const float* rgba) {
  return rgba[0] != 0 || rgba[1] != 0 || rgba[2] != 0;
}

// The depths of the hit points whose shadow rays can change `image`: its depth where some
// shadowing light's term (shadow_terms, as apply_shadows takes them) has a color, +infinity
// elsewhere. Where every term is black (the lights do not reach the point, or light it in
// black) apply_shadows removes nothing whether the point is occluded or not, so its rays are
// left out: with the surface facing away from a light, about half the hit points.
std::vector<float> shadow_ray_depths(const Framebuffer& image,
                                     std::span<const Framebuffer> shadow_terms);

// Removes from each pixel of `image` the part of its color each occluded light gave
// (shadow_terms[j], written by trace_into with the same options and composited like the image).
void apply_shadows(Framebuffer& image, std::span<const Framebuffer> shadow_terms,
                   std::span<const std::uint8_t> occluded);

}  // namespace tetray::render
