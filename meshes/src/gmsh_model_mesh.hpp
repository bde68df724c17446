#pragma once
// Conversion of the mesh held in the current gmsh model into a Mesh (through an MshModel, see
// msh_model.hpp): linear 2D cells only, in the plane z = 0, in named physical groups.

#include <string>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes::detail {

/// Reads the current gmsh model's mesh. Cells come from the physical surface groups (bodies),
/// boundary edges from the physical curve groups. Cells are made counter-clockwise and
/// boundary edges follow their cells. `source` names the model in error messages.
Mesh mesh_from_gmsh_model(const std::string& source);

}  // namespace ddafrac::meshes::detail
