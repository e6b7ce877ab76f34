// tetray's views of the rank's hexahedra and temperature (no copies: they point into the mesh).
#pragma once

#include <tetray/adaptor.hpp>

#include "local_hex_mesh.hpp"

// Without `ghost_flags` the ghost cells are passed like owned ones (drawn by two ranks).
tetray::MeshView hex_mesh_view(const LocalHexMesh& mesh, bool ghost_flags = true);
tetray::FieldView temperature_view(const LocalHexMesh& mesh);
