#include "scene_shadows.hpp"

#include <exception>
#include <string>

#include "render/composite/composite.hpp"
#include "render/composite/shadow_visibility.hpp"
#include "render/trace/shadow_rays.hpp"

namespace tetray {
namespace {

Status mpi_failure(const char* what, int rc) {
  return {StatusCode::mpi_error, std::string(what) + ": " + mpi_error_text(rc)};
}

}  // namespace

Status shadow_scene(render::Framebuffer& image, std::vector<render::Framebuffer>& terms,
                    const ShadowScene& scene, const Communicator& comm, int writer) {
  const bool split = comm.size > 1;
  if (split) {
    for (render::Framebuffer& term : terms) {
      const render::CompositeOptions options{.root = writer};
      if (const int rc = render::composite(term, comm.comm, options); rc != MPI_SUCCESS)
        return mpi_failure("compositing a shadowing light's term", rc);
    }
  }
  std::vector<float> depth(image.depth.begin(), image.depth.end());
  if (split) {
    if (const int rc = render::share_composited_depth(depth, writer, comm.comm); rc != MPI_SUCCESS)
      return mpi_failure("sharing the composited depth", rc);
  }
  Status traced = Status::success();
  std::vector<std::uint8_t> occluded;
  try {
    occluded = render::trace_shadow_rays(scene.volume, scene.bvh, scene.camera, scene.surfaces,
                                         scene.options, depth);
  } catch (const std::exception& error) {
    traced = {StatusCode::internal_error, std::string("tracing shadow rays: ") + error.what()};
    occluded.assign(depth.size(), 0);
  }
  if (split) {
    if (const int rc = render::combine_occlusion(occluded, writer, comm.comm); rc != MPI_SUCCESS)
      return mpi_failure("combining the shadow rays' occlusion", rc);
  }
  if (comm.rank == writer && traced.ok()) render::apply_shadows(image, terms, occluded);
  return traced;
}

}  // namespace tetray
