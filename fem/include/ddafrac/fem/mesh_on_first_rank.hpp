#pragma once
// Under mpirun the FEM's mesh is made once, by rank 0, which builds and partitions the whole
// triangulation and sends each rank only its part: the other ranks never hold the whole mesh
// (nor gmsh's peak memory while it meshes).

#include <functional>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::fem {

/// Runs `generate` on rank 0 only (collective: every rank must call it). Rank 0 gets the mesh;
/// the other ranks get a mesh holding only its boundary group names, all a model needs from it
/// on a rank that does not build the triangulation. A meshes::MeshError thrown by `generate` is
/// thrown on every rank with the same message, so no rank waits for a mesh that will not come.
meshes::Mesh mesh_on_first_rank(const std::function<meshes::Mesh()>& generate);

}  // namespace ddafrac::fem
