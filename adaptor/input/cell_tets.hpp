// A mesh given as cells (CellsView) becomes the tets the renderer reads: split once per topology
// change (cell_split.hpp) and kept until the next, with each tet's ghost flag that of its cell.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "tetray/adaptor.hpp"

namespace tetray {

class CellTets {
 public:
  // `out` is `mesh` with its cells replaced by their tets (split again when `topology_epoch`
  // differs from the last split's), or `mesh` itself when it holds no cells. Empty on success,
  // else what is wrong with the cells (the first bad cell, its type, the views).
  std::string resolve(const MeshView& mesh, std::uint64_t topology_epoch, MeshView& out);
  // The next resolve splits again, whatever its epoch.
  void forget() { epoch_ = ~std::uint64_t{0}; }

 private:
  std::string split(const MeshView& mesh);

  std::vector<std::int64_t> tets_;
  std::vector<std::uint8_t> ghost_;
  std::uint64_t epoch_ = ~std::uint64_t{0};
};

}  // namespace tetray
