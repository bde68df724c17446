#pragma once
// Straight lines of block edges through a mesh. A crack in DDA with virtual joints can only run
// along block edges, so a mesh whose interior edges line up into long straight lines offers a
// crack a straight path that a less regular mesh does not: a measure of mesh-induced crack bias.

#include <string>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes {

/// Largest turn (degrees) between consecutive edges of one straight line of edges.
inline constexpr double kStraightLineTurnDeg = 5.0;

/// The length (m) of the longest chain of interior edges of `body` (edges between two of its
/// cells) in which each edge continues the one before it, at their shared node, with a turn of
/// at most `max_turn_deg`; at every node the chain takes the straightest continuation. Throws
/// MeshError for an unknown body.
double longest_straight_edge_line(const Mesh& mesh, const std::string& body = "disc",
                                  double max_turn_deg = kStraightLineTurnDeg);

}  // namespace ddafrac::meshes
