// Smooth shading's vertex gradients of a volume split over ranks (docs/architecture.md, "Smooth
// shading across ranks"): a vertex on a face between two ranks' tets sees only its own rank's
// tets, so each rank's exact partial sums (render/update/vertex_gradients.hpp) are combined
// over the ranks that hold the vertex (shared_vertices.hpp). The result is bit for bit the
// gradient one rank holding every tet computes.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

#include "render/parallel/protocol_status.hpp"
#include "render/parallel/shared_vertices.hpp"
#include "render/volume/point_source.hpp"
#include "render/volume/tet_volume.hpp"

namespace tetray::render {

// The matching of shared vertices is kept from step to step: it costs an exchange of every
// boundary vertex's position and is needed again only when some rank's tets change.
class SharedGradients {
 public:
  // Collective. Finds the vertices of `volume` that other ranks hold too: the vertices of its
  // domain's boundary faces, matched by their reference coordinates in `points` (the caller's
  // points, whose numbering is the volume's point numbering; the displacement is not read).
  // Needed again after any rank's topology or set of rendered tets changed.
  ProtocolStatus match(const TetVolume& volume, const PointSource& points, MPI_Comm comm);

  // Collective over match's communicator: fills volume.gradients, update's three local passes
  // with the shared vertices' exponents, tet counts and sums combined over the ranks between
  // them. Like compute_vertex_gradients, only at the corners of the tets that straddle
  // `isovalues` (ascending; every vertex when empty), and at every shared vertex: each rank then
  // sums all its tets there, whichever rank's tets straddle.
  ProtocolStatus compute(TetVolume& volume, std::span<const float> isovalues = {}) const;

 private:
  SharedVertices shared_;
  std::vector<std::uint32_t> points_;  // the caller's point of each shared vertex, in its order
};

}  // namespace tetray::render
