// P1 element matrices and their assembly into rank-local matrices. Coefficients are per tet
// (materials are constant per tet).
#pragma once

#include <array>
#include <span>
#include <vector>

#include "minisolver/csr_matrix.hpp"
#include "minisolver/local_mesh.hpp"
#include "minisolver/tet_geometry.hpp"

namespace minisolver {

struct Lame {
  double lambda = 0;
  double mu = 0;
};

using ElasticBlock = std::array<double, 144>;  // 12x12 row-major, dof 3a+i

ElasticBlock elastic_element_matrix(const TetGeometry& g, const Lame& lame);

// Laplacian stiffness weighted by coefficient (conductivity), one dof per point.
CsrMatrix assemble_diffusion(const LocalMesh& mesh, std::shared_ptr<const SparsePattern> pattern,
                             std::span<const double> coefficient);
// Consistent mass weighted by density, the same for every component.
CsrMatrix assemble_mass(const LocalMesh& mesh, std::shared_ptr<const SparsePattern> pattern,
                        std::span<const double> density);
// Row-sum lumped mass (density * volume / 4 per point and component); partial sums.
std::vector<double> lumped_mass(const LocalMesh& mesh, int components,
                                std::span<const double> density);
CsrMatrix assemble_elasticity(const LocalMesh& mesh, std::shared_ptr<const SparsePattern> pattern,
                              std::span<const Lame> lame);

}  // namespace minisolver
