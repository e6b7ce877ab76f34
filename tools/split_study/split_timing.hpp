// What the cell split costs at a topology change: split_cells on a lattice of m^3 hexahedra,
// whole or with the half x >= 0 refined once (hanging nodes on the interface), with the
// hanging-node search and without it (as before tetray looked for hanging nodes).
#pragma once

#include <json/json.h>

#include <vector>

namespace tetray::tools {

// Prints a table (and returns its rows) for each m in `sizes`: cells, tets, hanging nodes found,
// and the best of `runs` split times with and without the search.
Json::Value split_timing(const std::vector<int>& sizes, int runs);

}  // namespace tetray::tools
