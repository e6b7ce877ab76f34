// What one rank hands tetray each rendered step: its locally owned and ghost active cells as VTK
// hexahedra over the vertices they use (numbered compactly), and the temperature at those
// vertices. Only standard types: the deal.II side fills it, the tetray side reads it, and neither
// sees the other's headers.
#pragma once

#include <cstdint>
#include <vector>

struct LocalHexMesh {
  std::vector<double> xyz;                 // 3 coordinates per point
  std::vector<std::uint8_t> types;         // VTK_HEXAHEDRON (12) per cell
  std::vector<std::int64_t> offsets;       // cells + 1 entries, 8 apart
  std::vector<std::int64_t> connectivity;  // 8 point indices per cell, in VTK's corner order
  std::vector<std::uint8_t> ghost;         // vtkGhostType per cell: 1 for deal.II's ghost cells
  std::vector<double> temperature;         // one value per point
};
