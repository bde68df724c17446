#include "gmsh_model_mesh.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <vector>

#include <fmt/format.h>

#include "cell_geometry.hpp"
#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes::detail {

namespace {

constexpr int kLine2 = 1;       // gmsh element type: 2-node line
constexpr int kTriangle3 = 2;   // 3-node triangle
constexpr int kQuadrangle4 = 3; // 4-node quadrangle
constexpr int kSurfaceDim = 2;
constexpr int kCurveDim = 1;
constexpr double kPlaneTolerance = 1e-9;  // |z| allowed, relative to the model's xy extent

struct ElementType {
  std::string name;
  int dim = 0;
  int order = 0;
};

ElementType element_type(int type) {
  ElementType t;
  int node_count = 0, primary_nodes = 0;
  std::vector<double> local_coords;
  gmsh::model::mesh::getElementProperties(type, t.name, t.dim, t.order, node_count, local_coords,
                                          primary_nodes);
  return t;
}

void check_element_types(const std::string& source) {
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types);
  for (int type : types) {
    const ElementType t = element_type(type);
    if (t.dim == 3) {
      throw MeshError(fmt::format("{}: holds 3D elements ({}); expected a 2D mesh", source, t.name));
    }
    if (t.order > 1) {
      throw MeshError(fmt::format(
          "{}: holds second-order (curved) elements ({}); expected linear triangles and "
          "quadrilaterals", source, t.name));
    }
    if (t.dim == kSurfaceDim && type != kTriangle3 && type != kQuadrangle4) {
      throw MeshError(fmt::format(
          "{}: holds unsupported 2D elements ({}); expected triangles and quadrilaterals", source,
          t.name));
    }
  }
}

struct NamedGroup {
  int tag = 0;
  std::string name;
};

std::vector<NamedGroup> named_groups(int dim, const std::string& source) {
  gmsh::vectorpair dim_tags;
  gmsh::model::getPhysicalGroups(dim_tags, dim);
  std::vector<NamedGroup> groups;
  for (const auto& [group_dim, tag] : dim_tags) {
    std::string name;
    gmsh::model::getPhysicalName(group_dim, tag, name);
    if (name.empty()) {
      throw MeshError(fmt::format("{}: physical {} group {} has no name; every group must be named",
                                  source, dim == kSurfaceDim ? "surface" : "curve", tag));
    }
    groups.push_back({tag, name});
  }
  return groups;
}

/// Every node of the model by tag, checked to lie in the plane z = 0.
std::map<std::size_t, Point> model_nodes(const std::string& source) {
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric, -1, -1, false, false);
  double extent = 0.0;
  for (std::size_t i = 0; i < tags.size(); ++i) {
    extent = std::max({extent, std::abs(coords[3 * i]), std::abs(coords[3 * i + 1])});
  }
  std::map<std::size_t, Point> nodes;
  for (std::size_t i = 0; i < tags.size(); ++i) {
    const double z = coords[3 * i + 2];
    if (std::abs(z) > kPlaneTolerance * extent) {
      throw MeshError(fmt::format("{}: node {} lies off the plane z = 0 (z = {}); expected a 2D "
                                  "mesh in the xy plane", source, tags[i], z));
    }
    nodes.emplace(tags[i], Point{coords[3 * i], coords[3 * i + 1]});
  }
  return nodes;
}

/// Collects cells and boundary edges by gmsh node tag, then numbers the nodes that cells use.
class MeshAssembler {
 public:
  explicit MeshAssembler(std::string source) : source_(std::move(source)) {}

  void add_cells(int entity, Index body) {
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, kSurfaceDim, entity);
    for (std::size_t t = 0; t < types.size(); ++t) {
      const std::size_t corners = types[t] == kTriangle3 ? 3 : 4;
      for (std::size_t e = 0; e < element_tags[t].size(); ++e) {
        cell_tags_.insert(cell_tags_.end(), node_tags[t].begin() + e * corners,
                          node_tags[t].begin() + (e + 1) * corners);
        cell_sizes_.push_back(corners);
        cell_body_.push_back(body);
      }
    }
  }

  void add_edges(int entity, Index group) {
    std::vector<std::size_t> element_tags, node_tags;
    gmsh::model::mesh::getElementsByType(kLine2, element_tags, node_tags, entity);
    for (std::size_t e = 0; e < element_tags.size(); ++e) {
      edges_.push_back({node_tags[2 * e], node_tags[2 * e + 1], group});
    }
  }

  Mesh finish(const std::map<std::size_t, Point>& model_nodes, std::vector<std::string> bodies,
              std::vector<std::string> boundaries) {
    Mesh mesh;
    std::map<std::size_t, Index> index_of;
    for (std::size_t tag : cell_tags_) index_of.emplace(tag, 0);
    for (auto& [tag, index] : index_of) {
      index = static_cast<Index>(mesh.nodes.size());
      mesh.nodes.push_back(model_nodes.at(tag));
    }
    for (std::size_t tag : cell_tags_) mesh.cell_nodes.push_back(index_of.at(tag));
    for (std::size_t size : cell_sizes_) {
      mesh.cell_offsets.push_back(mesh.cell_offsets.back() + static_cast<Index>(size));
    }
    mesh.cell_body = std::move(cell_body_);
    for (const auto& [a, b, group] : edges_) {
      if (index_of.count(a) == 0 || index_of.count(b) == 0) {
        throw MeshError(fmt::format("{}: boundary group \"{}\" has a line on nodes of no cell",
                                    source_, boundaries[group]));
      }
      mesh.boundary_edges.push_back({index_of.at(a), index_of.at(b), group});
    }
    mesh.body_names = std::move(bodies);
    mesh.boundary_names = std::move(boundaries);
    return mesh;
  }

 private:
  struct TaggedEdge {
    std::size_t a, b;
    Index group;
  };
  std::string source_;
  std::vector<std::size_t> cell_tags_;
  std::vector<std::size_t> cell_sizes_;
  std::vector<Index> cell_body_;
  std::vector<TaggedEdge> edges_;
};

/// Surface entities with elements must each belong to exactly one named body.
void check_surface_membership(const std::string& source) {
  gmsh::vectorpair surfaces;
  gmsh::model::getEntities(surfaces, kSurfaceDim);
  for (const auto& [dim, tag] : surfaces) {
    std::vector<int> types;
    gmsh::model::mesh::getElementTypes(types, dim, tag);
    std::vector<int> groups;
    gmsh::model::getPhysicalGroupsForEntity(dim, tag, groups);
    if (!types.empty() && groups.size() != 1) {
      throw MeshError(fmt::format(
          "{}: surface {} with elements is in {} physical surface groups; expected exactly one",
          source, tag, groups.size()));
    }
  }
}

}  // namespace

Mesh mesh_from_gmsh_model(const std::string& source) {
  check_element_types(source);
  const std::vector<NamedGroup> bodies = named_groups(kSurfaceDim, source);
  if (bodies.empty()) {
    throw MeshError(fmt::format(
        "{}: has no physical surface groups; every body must be a named physical surface", source));
  }
  const std::vector<NamedGroup> boundaries = named_groups(kCurveDim, source);
  check_surface_membership(source);

  MeshAssembler assembler(source);
  std::vector<std::string> body_names, boundary_names;
  for (const NamedGroup& body : bodies) {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(kSurfaceDim, body.tag, entities);
    for (int entity : entities) assembler.add_cells(entity, static_cast<Index>(body_names.size()));
    body_names.push_back(body.name);
  }
  for (const NamedGroup& boundary : boundaries) {
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(kCurveDim, boundary.tag, entities);
    for (int entity : entities) {
      assembler.add_edges(entity, static_cast<Index>(boundary_names.size()));
    }
    boundary_names.push_back(boundary.name);
  }
  Mesh mesh = assembler.finish(model_nodes(source), std::move(body_names),
                               std::move(boundary_names));
  orient_cells_counter_clockwise(mesh, source);
  orient_boundary_edges(mesh, source);
  return mesh;
}

}  // namespace ddafrac::meshes::detail
