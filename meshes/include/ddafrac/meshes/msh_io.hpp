#pragma once
// gmsh .msh files with named physical groups (surfaces = bodies, curves = boundary groups):
// written as ASCII MSH 4.1, read as ASCII MSH 4.1 or 2.2.

#include <filesystem>
#include <string_view>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes {

/// Writes the file whole (temporary name, then rename).
void write_msh(const Mesh& mesh, const std::filesystem::path& path);

/// Reads a 2D mesh of linear triangles/quadrilaterals with named physical surface groups from
/// an ASCII MSH 4.1 or 2.2 file. Throws MeshError naming the file (and the line) and what is
/// unsupported or malformed (binary or other versions, 3D or curved elements, unnamed or
/// missing physical groups; clockwise cells are reoriented, not rejected).
Mesh read_msh(const std::filesystem::path& path);

/// The same for the text of a .msh file (file_name is used in messages).
Mesh parse_msh(std::string_view text, const std::filesystem::path& file_name);

}  // namespace ddafrac::meshes
