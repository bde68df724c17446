#pragma once
// Plane geometry of the cells of a Mesh: area, interior angles, orientation.

#include <cstddef>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes::detail {

/// Signed area (m^2) of cell c: positive when its nodes run counter-clockwise.
double signed_area(const Mesh& mesh, std::size_t c);

/// The smallest interior angle of cell c, in degrees.
double min_interior_angle_deg(const Mesh& mesh, std::size_t c);

/// Reverses every clockwise cell; throws MeshError (naming `source`) on a cell of zero area.
void orient_cells_counter_clockwise(Mesh& mesh, const std::string& source);

/// Turns every boundary edge to run as in the cell that owns it; throws MeshError (naming
/// `source`) for a boundary edge that is no edge of any cell.
void orient_boundary_edges(Mesh& mesh, const std::string& source);

}  // namespace ddafrac::meshes::detail
