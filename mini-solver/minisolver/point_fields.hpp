// The point fields handed to the renderer: displacement magnitude, von Mises stress (constant per
// tet, averaged to points weighted by volume, across ranks) and the interior indicator (0 on the
// boundary, 1 inside; its 0.5 isosurface is a skin just inside the body's surface).
#pragma once

#include <span>
#include <vector>

#include "minisolver/dof_space.hpp"
#include "minisolver/elasticity.hpp"

namespace minisolver {

std::vector<double> magnitudes(std::span<const double> vectors);

// Von Mises stress of the displacement u (3 per point), per tet.
std::vector<double> von_mises_per_tet(const LocalMesh& mesh,
                                      const std::vector<ElasticMaterial>& materials,
                                      std::span<const double> u);

// Volume-weighted average of per-tet values at the points; `scalar_space` has one component.
std::vector<double> average_to_points(const DofSpace& scalar_space,
                                      std::span<const double> per_tet);

std::vector<double> interior_indicator(const LocalMesh& mesh);

}  // namespace minisolver
