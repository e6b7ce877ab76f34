// Direct volume rendering of the point field along the walk (docs/architecture.md §8): every
// pixel's ray walks the tets from the boundary face it enters through; each tet's stretch is
// integrated exactly in the linear field (segment_integral.hpp) and gathered front to back; a
// run of tets from an entry to the next exit of the domain becomes one fragment, so a
// non-convex domain gives several per pixel and ranks' fragments merge in depth order
// (render/core/fragments.hpp, render/composite/fragment_composite.hpp). A run stops early once
// its opacity reaches `termination`. Isosurfaces, of the volume's field or of a second one, are
// layers along the walk (surface_crossing.hpp): the stretch is split where the ray crosses one
// and the lit surface is laid over the run in order, so surfaces and volume make one image.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/bvh/bvh.hpp"
#include "render/core/fragments.hpp"
#include "render/scene/camera.hpp"
#include "render/scene/iso_surface.hpp"
#include "render/walk/boundary_faces.hpp"
#include "render/walk/face_adjacency.hpp"
#include "render/walk/transfer_function.hpp"

namespace tetray::render {

struct VolumeRenderOptions {
  TransferFunction transfer;
  double termination = 0.99;  // opacity that ends a run; >= 1: never (no early termination)
  // > 0: fixed-step sampling at this distance (fixed_step.hpp) instead of the exact integral,
  // the baseline of the error-against-time study.
  double sample_step = 0;
  // Isosurfaces met along the walk, with their colors and opacities, of `surface_field` (per
  // vertex of the vertex store; empty: the volume's own field), lit by the headlight with
  // `ambient` (TraceOptions::ambient).
  std::vector<IsoSurface> surfaces;
  std::span<const float> surface_field;
  double ambient = 0.15;
  // The tet holding the camera's eye (locate_eye): every ray's walk starts there; kBoundaryFace:
  // the eye lies outside this rank's tets, rays start at the boundary faces they enter through.
  std::uint32_t eye_tet = kBoundaryFace;
  // The volume's BVH: rays skip its empty tets (empty_space.hpp) with the exact integral; null,
  // or with fixed-step sampling (whose samples follow from where a run starts): every tet of a
  // ray's way is walked.
  const Bvh* bvh = nullptr;
};

struct VolumeRenderStats {
  std::uint64_t rays = 0;
  std::uint64_t tets_visited = 0;
  std::uint64_t entries = 0;
  std::uint64_t lost_rays = 0;        // ended by the walk's step bound
  std::uint64_t terminated_runs = 0;  // ended early at the termination opacity
  std::uint64_t jumps = 0;            // over empty space
  std::uint64_t busy_tets = 0;        // tets not empty for the scene (all without skipping)
};

// The walk structures of a volume: built on a topology change or a BVH rebuild, the boundary
// faces refit when the geometry moves.
struct WalkStructure {
  FaceAdjacency<Tet20> adjacency;
  BoundaryFaces boundary;

  std::size_t bytes() const { return adjacency.bytes() + boundary.bytes(); }
};
WalkStructure build_walk_structure(const TetVolume& volume);

// The tet of `volume` holding the eye of `camera` (world coordinates), or kBoundaryFace.
std::uint32_t locate_eye(const TetVolume& volume, const Bvh& bvh, const Camera& camera);

// The fragments of every pixel of `camera` (world coordinates; the volume's are local). Parallel
// over rows in the calling oneTBB arena; the result does not depend on the thread count.
VolumeFragmentImage render_volume(const TetVolume& volume, const WalkStructure& walk,
                                  const Camera& camera, const VolumeRenderOptions& options,
                                  VolumeRenderStats* stats = nullptr);

}  // namespace tetray::render
