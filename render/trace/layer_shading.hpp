// The rank-local steps after depth peeling (trace.hpp, trace_layers) that turn a pixel's kept
// layers into its color: each layer's shadows removed (its shadow terms, as apply_shadows does for
// a first hit) and the layers blended front to back with the first layer's view depth. The
// adaptor runs them on the writer after the fragment compositor (render/parallel/scene_layers.hpp).
#pragma once

#include <cstdint>
#include <span>

#include "render/core/fragments.hpp"
#include "render/core/framebuffer.hpp"
#include "render/scene/camera.hpp"

namespace tetray::render {

// Removes from layer `layer` of each pixel of `color` the part each occluded light gave
// (bit j of occluded[p]: shadowing light j; shadow_terms[j] has the same fragments as `color`).
void apply_layer_shadows(FragmentImage& color, std::span<const FragmentImage> shadow_terms,
                         int layer, std::span<const std::uint8_t> occluded);

// Leaves out of layer `layer`'s shadow rays (its view depths, layer_view_depths) the pixels whose
// every shadowing light's term of that layer is black: apply_layer_shadows removes nothing there,
// occluded or not (shadow_ray_depths does the same for a first hit).
void keep_lit_layer_points(std::span<const FragmentImage> shadow_terms, int layer,
                           std::span<float> depth);

// The blended image of the layers (sorted and kept as the fragment merge keeps them), with the
// first layer's view depth and key, into `image` (its storage reused).
void flatten_layers(FragmentImage& layers, const Camera& camera, Framebuffer& image);

}  // namespace tetray::render
