#include "gmsh_model_mesh.hpp"

#include <gmsh.h>

#include <cstddef>
#include <vector>

#include "msh_model.hpp"

namespace ddafrac::meshes::detail {

namespace {

ElementKind element_kind(int type) {
  ElementKind kind;
  int node_count = 0, primary_nodes = 0;
  std::vector<double> local_coords;
  gmsh::model::mesh::getElementProperties(type, kind.name, kind.dim, kind.order, node_count, local_coords,
                                          primary_nodes);
  return kind;
}

void check_element_types(const std::string& source) {
  std::vector<int> types;
  gmsh::model::mesh::getElementTypes(types);
  for (int type : types) check_element_kind(type, element_kind(type), source);
}

/// The entities of dimension `dim` with their physical groups and elements, and the names of
/// those groups.
void add_entities(int dim, MshModel& model) {
  gmsh::vectorpair dim_tags;
  gmsh::model::getPhysicalGroups(dim_tags, dim);
  for (const auto& [group_dim, tag] : dim_tags) {
    gmsh::model::getPhysicalName(group_dim, tag, model.group_names[{group_dim, tag}]);
  }
  gmsh::vectorpair entities;
  gmsh::model::getEntities(entities, dim);
  for (const auto& [entity_dim, tag] : entities) {
    MshEntity& entity = model.entities[{entity_dim, tag}];
    std::vector<int> groups;
    gmsh::model::getPhysicalGroupsForEntity(entity_dim, tag, groups);
    entity.groups.insert(groups.begin(), groups.end());
    std::vector<int> types;
    std::vector<std::vector<std::size_t>> element_tags, node_tags;
    gmsh::model::mesh::getElements(types, element_tags, node_tags, entity_dim, tag);
    for (std::size_t t = 0; t < types.size(); ++t) entity.elements[types[t]] = std::move(node_tags[t]);
  }
}

}  // namespace

Mesh mesh_from_gmsh_model(const std::string& source) {
  check_element_types(source);
  MshModel model;
  add_entities(kSurfaceDim, model);
  add_entities(kCurveDim, model);
  std::vector<std::size_t> tags;
  std::vector<double> coords, parametric;
  gmsh::model::mesh::getNodes(tags, coords, parametric, -1, -1, false, false);
  for (std::size_t i = 0; i < tags.size(); ++i) {
    model.nodes[tags[i]] = {coords[3 * i], coords[3 * i + 1], coords[3 * i + 2]};
  }
  return mesh_from_model(model, source);
}

}  // namespace ddafrac::meshes::detail
