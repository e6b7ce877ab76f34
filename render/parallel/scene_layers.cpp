#include "render/parallel/scene_layers.hpp"

#include <mpi.h>

#include <algorithm>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "render/composite/fragment_composite.hpp"
#include "render/parallel/comm_place.hpp"
#include "render/parallel/shadow_visibility.hpp"
#include "render/trace/layer_shading.hpp"
#include "render/trace/shadow_rays.hpp"

namespace tetray::render {
namespace {

// The most layers any pixel kept.
int deepest(const FragmentImage& layers) {
  std::uint32_t most = 0;
  for (std::size_t p = 0; p < layers.pixel_count(); ++p)
    most = std::max(most, layers.begin[p + 1] - layers.begin[p]);
  return static_cast<int>(most);
}

// Collective: the shadows of every kept layer (the writer's `merged` and `terms`), layer by layer.
ProtocolStatus shadow_layers(FragmentImage& merged, const std::vector<FragmentImage>& terms,
                             const ShadowScene& scene, bool is_writer, int writer, MPI_Comm comm) {
  int layers = is_writer ? deepest(merged) : 0;
  if (const int rc = MPI_Bcast(&layers, 1, MPI_INT, writer, comm); rc != MPI_SUCCESS)
    return mpi_failure("sharing the layer count", rc);
  const std::size_t pixels =
      static_cast<std::size_t>(scene.camera.width) * static_cast<std::size_t>(scene.camera.height);
  std::vector<float> depth(pixels);
  ProtocolStatus traced = ProtocolStatus::success();
  for (int layer = 0; layer < layers; ++layer) {
    if (is_writer) {
      layer_view_depths(merged, scene.camera, layer, depth);
      keep_lit_layer_points(terms, layer, depth);
    }
    if (const int rc = share_composited_depth(depth, writer, comm); rc != MPI_SUCCESS)
      return mpi_failure("sharing a layer's depth", rc);
    std::vector<std::uint8_t> occluded;
    try {
      if (traced.ok())
        occluded = trace_shadow_rays(scene.volume, scene.bvh, scene.camera, scene.surfaces,
                                     scene.options, depth);
    } catch (const std::exception& error) {
      traced = {ProtocolStatus::Code::local_error,
                std::string("tracing shadow rays: ") + error.what()};
    }
    occluded.resize(pixels, 0);
    if (const int rc = combine_occlusion(occluded, writer, comm); rc != MPI_SUCCESS)
      return mpi_failure("combining the shadow rays' occlusion", rc);
    if (is_writer && traced.ok()) apply_layer_shadows(merged, terms, layer, occluded);
  }
  return traced;
}

// Without shadows nothing needs the merged layers on the writer: each rank merges and blends
// the layers of its stripe of the image, its first layers' distances made view depths there
// (fragment_composite.hpp, composite_fragments).
ProtocolStatus blend_in_stripes(const LayerImage& local, const ShadowScene& scene, int writer,
                                MPI_Comm comm, Framebuffer& image, MergedLayers& kept) {
  FragmentCompositeOptions options;
  options.max_layers = static_cast<std::size_t>(scene.options.max_layers);
  options.stripe_depths = [&camera = scene.camera](std::size_t first, std::span<float> depth) {
    view_depths_of_distances(camera, first, depth);
  };
  const int rc =
      composite_fragments(local.color, comm, writer, image, options, nullptr, &kept.stripes);
  if (rc != MPI_SUCCESS) return mpi_failure("compositing the layers", rc);
  return ProtocolStatus::success();
}

}  // namespace

ProtocolStatus composite_layers(LayerImage& local, const ShadowScene& scene, int writer,
                                MPI_Comm comm, Framebuffer& image, MergedLayers& kept) {
  CommPlace place;
  if (const int rc = place_in(comm, place); rc != MPI_SUCCESS)
    return mpi_failure("layers: the rank's place", rc);
  // Alone, the rank's layers are already the kept ones (at most max_layers per pixel, which
  // flatten_layers orders as the merge would): they are blended where they are, with no copy.
  const bool alone = place.size == 1;
  const auto max_layers = static_cast<std::size_t>(scene.options.max_layers);
  if (!alone && local.shadow_terms.empty())
    return blend_in_stripes(local, scene, writer, comm, image, kept);
  kept.shadow_terms.resize(alone ? 0 : local.shadow_terms.size());
  FragmentImage& merged = alone ? local.color : kept.color;
  std::vector<FragmentImage>& terms = alone ? local.shadow_terms : kept.shadow_terms;
  if (!alone) {
    if (const int rc = gather_fragments(local.color, comm, writer, max_layers, kept.color);
        rc != MPI_SUCCESS)
      return mpi_failure("compositing the layers", rc);
    for (std::size_t j = 0; j < terms.size(); ++j) {
      // The same depths, keys and alphas as the colors: each pixel keeps the same fragments.
      const int rc = gather_fragments(local.shadow_terms[j], comm, writer, max_layers, terms[j]);
      if (rc != MPI_SUCCESS) return mpi_failure("compositing a shadowing light's layers", rc);
    }
  }
  ProtocolStatus shadowed = ProtocolStatus::success();
  if (!terms.empty()) {
    shadowed = shadow_layers(merged, terms, scene, place.rank == writer, writer, comm);
    if (shadowed.code == ProtocolStatus::Code::mpi_error) return shadowed;
  }
  if (place.rank == writer) flatten_layers(merged, scene.camera, image);
  return shadowed;
}

}  // namespace tetray::render
