// Smooth shading's vertex gradients of a volume split over ranks (docs/architecture.md, "Smooth
// shading across ranks"): a vertex on a face between two ranks' tets sees only its own rank's
// tets, so each rank's exact partial sums (render/update/vertex_gradients.hpp) are combined
// over the ranks that hold the vertex (render/composite/shared_vertices.hpp). The result is
// bit for bit the gradient one rank holding every tet computes.
#pragma once

#include <mpi.h>

#include <cstdint>
#include <string>
#include <vector>

#include "render/composite/shared_vertices.hpp"
#include "render/volume/tet_volume.hpp"
#include "tetray/adaptor.hpp"

namespace tetray {

class SharedGradients {
 public:
  // Collective. Finds the vertices of `volume` that other ranks hold too: the vertices of its
  // domain's boundary faces, matched by their reference coordinates in `points` (the caller's
  // points, whose numbering is the volume's point numbering). Needed again after any rank's
  // topology or set of rendered tets changed. Returns an error message, empty on success.
  std::string match(const render::TetVolume& volume, const PointsView& points, MPI_Comm comm);

  // Collective. Fills volume.gradients, summing over the ranks at the shared vertices.
  std::string compute(render::TetVolume& volume) const;

 private:
  render::SharedVertices shared_;
  std::vector<std::uint32_t> points_;  // the caller's point of each shared vertex, in its order
};

}  // namespace tetray
