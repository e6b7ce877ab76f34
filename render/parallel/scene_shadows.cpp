#include "render/parallel/scene_shadows.hpp"

#include <exception>
#include <string>

#include "render/composite/composite.hpp"
#include "render/parallel/comm_place.hpp"
#include "render/parallel/shadow_visibility.hpp"
#include "render/trace/shadow_rays.hpp"

namespace tetray::render {

ProtocolStatus shadow_across_ranks(Framebuffer& image, std::vector<Framebuffer>& terms,
                                   const ShadowScene& scene, int writer, MPI_Comm comm,
                                   std::vector<std::uint8_t>* occluded_out) {
  CommPlace place;
  if (const int rc = place_in(comm, place); rc != MPI_SUCCESS)
    return mpi_failure("shadows: the rank's place", rc);
  const bool split = place.size > 1;
  if (split) {
    for (Framebuffer& term : terms) {
      const CompositeOptions options{.root = writer, .active_hint = {}};
      if (const int rc = composite(term, comm, options); rc != MPI_SUCCESS)
        return mpi_failure("compositing a shadowing light's term", rc);
    }
  }
  // The writer's hit points that a shadowing light reaches; the others' is broadcast over it.
  std::vector<float> depth = place.rank == writer ? shadow_ray_depths(image, terms)
                                                  : std::vector<float>(image.depth.size());
  if (split) {
    if (const int rc = share_composited_depth(depth, writer, comm); rc != MPI_SUCCESS)
      return mpi_failure("sharing the composited depth", rc);
  }
  ProtocolStatus traced = ProtocolStatus::success();
  std::vector<std::uint8_t> occluded;
  try {
    occluded = trace_shadow_rays(scene.volume, scene.bvh, scene.camera, scene.surfaces,
                                 scene.options, depth);
  } catch (const std::exception& error) {
    traced = {ProtocolStatus::Code::local_error,
              std::string("tracing shadow rays: ") + error.what()};
    occluded.assign(depth.size(), 0);
  }
  if (split) {
    if (const int rc = combine_occlusion(occluded, writer, comm); rc != MPI_SUCCESS)
      return mpi_failure("combining the shadow rays' occlusion", rc);
  }
  if (place.rank == writer && traced.ok()) apply_shadows(image, terms, occluded);
  if (occluded_out != nullptr) *occluded_out = std::move(occluded);
  return traced;
}

}  // namespace tetray::render
