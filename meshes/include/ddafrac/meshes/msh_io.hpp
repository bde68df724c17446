#pragma once
// ASCII gmsh 4.1 files with named physical groups (surfaces = bodies, curves = boundary groups).

#include <filesystem>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes {

/// Writes the file whole (temporary name, then rename).
void write_msh(const Mesh& mesh, const std::filesystem::path& path);

/// Reads a 2D mesh of linear triangles/quadrilaterals with named physical surface groups.
/// Throws MeshError naming the file and what is unsupported (3D or curved elements, unnamed
/// or missing physical groups, clockwise cells are reoriented, not rejected).
Mesh read_msh(const std::filesystem::path& path);

}  // namespace ddafrac::meshes
