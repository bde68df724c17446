#pragma once
// A PNG picture of a mesh so that a person can look at it: bodies in different colours,
// cell edges thin, boundary groups such as a slit or joint drawn thick.

#include <cstddef>
#include <filesystem>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes {

struct PictureOptions {
  int width_px = 1200;
  bool draw_cell_edges = true;
};

/// The fill colour of body `body` (an index into Mesh::body_names) in the picture.
struct Rgb {
  unsigned char r = 0, g = 0, b = 0;
};
Rgb body_colour(std::size_t body);

/// Writes the file whole (temporary name, then rename).
void write_mesh_png(const Mesh& mesh, const std::filesystem::path& path, const PictureOptions& options = {});

}  // namespace ddafrac::meshes
