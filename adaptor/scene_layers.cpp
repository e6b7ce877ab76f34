#include "scene_layers.hpp"

#include <mpi.h>

#include <algorithm>
#include <exception>
#include <limits>
#include <string>
#include <vector>

#include "render/composite/fragment_composite.hpp"
#include "render/composite/shadow_visibility.hpp"
#include "render/trace/layer_shading.hpp"
#include "render/trace/shadow_rays.hpp"

namespace tetray {
namespace {

Status mpi_failure(const char* what, int rc) {
  return {StatusCode::mpi_error, std::string(what) + ": " + mpi_error_text(rc)};
}

// The most layers any pixel kept.
int deepest(const render::FragmentImage& layers) {
  std::uint32_t most = 0;
  for (std::size_t p = 0; p < layers.pixel_count(); ++p)
    most = std::max(most, layers.begin[p + 1] - layers.begin[p]);
  return static_cast<int>(most);
}

// Collective: the shadows of every kept layer (the writer's `merged` and `terms`), layer by layer.
Status shadow_layers(render::FragmentImage& merged, const std::vector<render::FragmentImage>& terms,
                     const ShadowScene& scene, const Communicator& comm, int writer) {
  const bool is_writer = comm.rank == writer;
  int layers = is_writer ? deepest(merged) : 0;
  if (const int rc = MPI_Bcast(&layers, 1, MPI_INT, writer, comm.comm); rc != MPI_SUCCESS)
    return mpi_failure("sharing the layer count", rc);
  const std::size_t pixels =
      static_cast<std::size_t>(scene.camera.width) * static_cast<std::size_t>(scene.camera.height);
  std::vector<float> depth(pixels);
  Status traced = Status::success();
  for (int layer = 0; layer < layers; ++layer) {
    if (is_writer) render::layer_view_depths(merged, scene.camera, layer, depth);
    if (const int rc = render::share_composited_depth(depth, writer, comm.comm); rc != MPI_SUCCESS)
      return mpi_failure("sharing a layer's depth", rc);
    std::vector<std::uint8_t> occluded;
    try {
      if (traced.ok())
        occluded = render::trace_shadow_rays(scene.volume, scene.bvh, scene.camera, scene.surfaces,
                                             scene.options, depth);
    } catch (const std::exception& error) {
      traced = {StatusCode::internal_error, std::string("tracing shadow rays: ") + error.what()};
    }
    occluded.resize(pixels, 0);
    if (const int rc = render::combine_occlusion(occluded, writer, comm.comm); rc != MPI_SUCCESS)
      return mpi_failure("combining the shadow rays' occlusion", rc);
    if (is_writer && traced.ok()) render::apply_layer_shadows(merged, terms, layer, occluded);
  }
  return traced;
}

}  // namespace

Status composite_layers(const render::LayerImage& local, const ShadowScene& scene,
                        const Communicator& comm, int writer, render::Framebuffer& image) {
  const auto max_layers = static_cast<std::size_t>(scene.options.max_layers);
  render::FragmentImage merged;
  if (const int rc = render::gather_fragments(local.color, comm.comm, writer, max_layers, merged);
      rc != MPI_SUCCESS)
    return mpi_failure("compositing the layers", rc);
  std::vector<render::FragmentImage> terms(local.shadow_terms.size());
  for (std::size_t j = 0; j < terms.size(); ++j) {
    // The same depths, keys and alphas as the colors: each pixel keeps the same fragments.
    const int rc =
        render::gather_fragments(local.shadow_terms[j], comm.comm, writer, max_layers, terms[j]);
    if (rc != MPI_SUCCESS) return mpi_failure("compositing a shadowing light's layers", rc);
  }
  Status shadowed = Status::success();
  if (!terms.empty()) {
    shadowed = shadow_layers(merged, terms, scene, comm, writer);
    if (shadowed.code == StatusCode::mpi_error) return shadowed;
  }
  if (comm.rank == writer) render::flatten_layers(merged, scene.camera, image);
  return shadowed;
}

}  // namespace tetray
