// Where a view's rays can enter a rank's domain, binned on the screen: a ray from the eye enters
// only through a boundary face whose outer side faces the eye, and only where the face projects,
// so the faces facing the eye are sorted into tiles of pixels by the rectangle of the pixel
// centres their projection can hold. A pixel's ray then tests the faces of its tile,
// and those that cross the plane of the eye (which project nowhere) wherever it is, instead of
// searching the boundary faces' tree (boundary_faces.hpp) for its first entry and for each entry
// after it leaves the domain. Faces wholly behind the eye are left out (rays run forward from
// it). The candidates hold every face the exact entry test can accept, so
// the entries, and the images, are the tree's.
#pragma once

#include <cstdint>
#include <span>
#include <vector>

#include "render/scene/camera.hpp"
#include "render/walk/boundary_faces.hpp"

namespace tetray::render {

struct EntryBins {
  static constexpr int kTile = 8;  // pixels a side
  int tiles_x = 0, tiles_y = 0;
  std::vector<std::uint32_t> begin;       // per tile (row-major) + 1, into faces
  std::vector<std::uint32_t> faces;       // indices into BoundaryFaces::faces, ascending per tile
  std::vector<std::uint32_t> everywhere;  // facing faces that cross the eye's plane

  // False where the view's faces were not binned (too many tiles for them): search the tree.
  bool usable() const { return !begin.empty(); }

  EntryCandidates at(int i, int j) const {
    const auto tile = static_cast<std::size_t>((j / kTile) * tiles_x + i / kTile);
    return {std::span(faces).subspan(begin[tile], begin[tile + 1] - begin[tile]), everywhere};
  }
};

// The bins of `camera` (world coordinates; the volume's are local); not usable() when the faces
// would cover more than 16 tiles each on average.
EntryBins bin_entry_faces(const TetVolume& volume, const BoundaryFaces& boundary,
                          const Camera& camera);

}  // namespace tetray::render
