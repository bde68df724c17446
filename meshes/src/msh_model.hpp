#pragma once
// A 2D mesh as gmsh holds it, in a model or in a .msh file: nodes by tag, entities with their
// physical groups and elements, and the groups' names. The gmsh API (generated meshes) and
// ddafrac's own .msh parser (users' files) each fill one; one conversion, with the checks a
// user's file needs, turns it into a Mesh.

#include <array>
#include <cstddef>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes::detail {

// gmsh element types that a 2D mesh of linear cells holds.
inline constexpr int kLine2 = 1;        // 2-node line
inline constexpr int kTriangle3 = 2;    // 3-node triangle
inline constexpr int kQuadrangle4 = 3;  // 4-node quadrangle
inline constexpr int kPoint1 = 15;      // 1-node point

/// Nodes of an element of one of the four types above (0 for any other type).
constexpr std::size_t linear_node_count(int type) {
  return type == kPoint1 ? 1 : type == kLine2 ? 2 : type == kTriangle3 ? 3 : type == kQuadrangle4 ? 4 : 0;
}

inline constexpr int kPointDim = 0;
inline constexpr int kCurveDim = 1;
inline constexpr int kSurfaceDim = 2;
inline constexpr int kVolumeDim = 3;

/// What gmsh says of an element type: its name ("Triangle 3"), dimension and order.
struct ElementKind {
  std::string name;
  int dim = 0;
  int order = 0;
};

/// Throws MeshError (naming `source`) unless `kind` is a point, a 2-node line, a 3-node
/// triangle or a 4-node quadrangle.
void check_element_kind(int type, const ElementKind& kind, const std::string& source);

struct MshEntity {
  std::set<int> groups;  // tags of the physical groups (of the entity's dimension) it is in
  /// Node tags of its elements by element type, the elements one after another.
  std::map<int, std::vector<std::size_t>> elements;
};

struct MshModel {
  std::map<std::size_t, std::array<double, 3>> nodes;      // x, y, z by node tag
  std::map<std::pair<int, int>, MshEntity> entities;       // by (dim, tag)
  std::map<std::pair<int, int>, std::string> group_names;  // by (dim, physical tag)
};

/// The cells of the named physical surface groups (bodies), the lines of the named physical
/// curve groups (boundary groups), checked (2D, in the plane z = 0, every group named, every
/// surface with elements in one body) and made counter-clockwise. Element types must have been
/// checked with check_element_kind. `source` names the model in error messages.
Mesh mesh_from_model(const MshModel& model, const std::string& source);

}  // namespace ddafrac::meshes::detail
