// The faces where rays enter a rank's domain, in a small binary BVH of their own (median splits,
// 4 faces a leaf): a ray starts its walk at the nearest boundary face it enters through at
// t >= t_from, and after leaving the domain looks for the next one (non-convex domains and
// sub-domains). Entries are ordered by (t, face index) and each must come after the previous one,
// so re-entering a non-convex domain can never cycle. The tree is built once per adjacency (the
// faces depend on topology only) and refit when the geometry moves. A camera inside the mesh: the
// eye's tet is located once per frame through the volume's BVH (point_locate.hpp, locate_eye) and
// each ray's walk starts there from the face its line enters the tet through behind the eye
// (entry_behind, the same ray_side test as a boundary entry, so exactly one face), its first
// stretch cut at t = 0; Tet20 only (Tet16 decodes a neighbour from the one the walk came from,
// unknown behind the eye).
//
// Why not render/bvh: that tree bounds tets in 4D (the field's range, for iso-range culling),
// reorders TetVolume::tets into its leaf order and splits by BIH or SAH; this one bounds
// triangles (faces, no field) by a median split of their centres, traversed in double with
// padded boxes. Entries at equal t are ordered by face index in this leaf order, so another
// builder would reorder the faces and could change which face a walk enters first.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "render/volume/tet_volume.hpp"
#include "render/walk/face_adjacency.hpp"
#include "render/walk/face_crossing.hpp"
#include "render/walk/ray_frame.hpp"

namespace tetray::render {

struct BoundaryFace {
  std::uint32_t vertex[3];
  std::uint32_t opposite_vertex;  // the tet's fourth vertex, on the domain's side
  std::uint32_t tet;
};

struct BoundaryNode {
  float lo[3], hi[3];
  std::uint32_t first;  // inner: the first child (the second is first + 1); leaf: first face
  std::uint32_t count;  // leaf: faces (>= 1); inner: 0
};

struct BoundaryFaces {
  std::vector<BoundaryFace> faces;  // in leaf order
  std::vector<BoundaryNode> nodes;  // nodes[0] is the root; children after their parent

  std::size_t bytes() const {
    return faces.capacity() * sizeof(BoundaryFace) + nodes.capacity() * sizeof(BoundaryNode);
  }
};

BoundaryFaces build_boundary_faces(const TetVolume& volume,
                                   std::span<const BoundaryFaceRef> boundary);

// New node bounds from the vertex store as it is.
void refit_boundary_faces(const TetVolume& volume, BoundaryFaces& boundary);

// Where a walk enters the domain: the face, counter-clockwise around the ray, and the crossing.
struct FaceEntry {
  std::uint32_t face = 0;  // index into BoundaryFaces::faces
  std::uint32_t tet = 0;
  ProjectedFace projected{};
  FaceCrossing crossing{};
};

// Entries are ordered by (t, face index); a walk asks for the first one after the previous.
struct EntryCursor {
  double t = 0;
  std::uint32_t face = 0;
  bool any = false;  // false: no entry yet, every (t, face) is after the cursor
};

// The only faces a ray may enter through, where a view has binned them (entry_bins.hpp):
// next_entry then tests these instead of searching the tree.
struct EntryCandidates {
  std::span<const std::uint32_t> tile;        // the faces of the ray's tile of pixels
  std::span<const std::uint32_t> everywhere;  // faces every ray of the view must test
};

// Where a walk starting inside tet `tet` (the eye's, point_locate.hpp) comes from: the tet's
// face the ray's line enters it through, behind the eye (crossing.t <= 0), with `face` set to
// kBoundaryFace. Empty only for a degenerate tet.
std::optional<FaceEntry> entry_behind(const TetVolume& volume, const RayFrame& frame,
                                      std::uint32_t tet, std::span<const float> second = {});

// The first face, in (t, face) order and after `after`, through which the ray enters the domain
// at t >= t_from; `second` as for cross_face; `candidates`: the faces to test (they must hold
// every face the ray enters through), null: search the tree.
std::optional<FaceEntry> next_entry(const TetVolume& volume, const BoundaryFaces& boundary,
                                    const RayFrame& frame, double t_from, EntryCursor after,
                                    std::span<const float> second = {},
                                    const EntryCandidates* candidates = nullptr);

}  // namespace tetray::render
