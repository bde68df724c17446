#pragma once
// A 2D polygon mesh: the common currency between the mesh generators, the .msh reader/writer,
// the DDA (every cell is a block) and the FEM (cells are finite elements).

#include <cstdint>
#include <string>
#include <vector>

namespace ddafrac::meshes {

using Index = std::uint32_t;

struct Point {
  double x = 0.0;  // m
  double y = 0.0;  // m
};

/// An edge of a named boundary group (disc rim, flats, slit faces, impact patch, ...).
struct BoundaryEdge {
  Index a = 0;  // node indices, in the counter-clockwise order of the cell that owns the edge
  Index b = 0;
  Index group = 0;  // index into Mesh::boundary_names
};

/// Cells are polygons stored as a compressed list (arrays, not pointers, so that OpenMP loops
/// can walk them): cell c has the nodes cell_nodes[cell_offsets[c] .. cell_offsets[c+1]),
/// counter-clockwise, and belongs to body cell_body[c].
struct Mesh {
  std::vector<Point> nodes;
  std::vector<Index> cell_offsets{0};
  std::vector<Index> cell_nodes;
  std::vector<Index> cell_body;
  std::vector<std::string> body_names;  // physical surface groups
  std::vector<BoundaryEdge> boundary_edges;
  std::vector<std::string> boundary_names;  // physical curve groups

  std::size_t cell_count() const { return cell_body.size(); }
  std::size_t cell_size(std::size_t c) const { return cell_offsets[c + 1] - cell_offsets[c]; }
  const Index* cell_begin(std::size_t c) const { return cell_nodes.data() + cell_offsets[c]; }
};

}  // namespace ddafrac::meshes
