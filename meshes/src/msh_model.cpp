#include "msh_model.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "cell_geometry.hpp"
#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes::detail {

namespace {

constexpr double kPlaneTolerance = 1e-9;  // |z| allowed, relative to the model's xy extent

struct NamedGroup {
  int tag = 0;
  std::string name;
};

/// The physical groups of dimension `dim` that hold entities, by tag; each must have a name.
std::vector<NamedGroup> named_groups(const MshModel& model, int dim, const std::string& source) {
  std::set<int> tags;
  for (const auto& [key, entity] : model.entities) {
    if (key.first == dim) tags.insert(entity.groups.begin(), entity.groups.end());
  }
  std::vector<NamedGroup> groups;
  for (int tag : tags) {
    const auto name = model.group_names.find({dim, tag});
    if (name == model.group_names.end() || name->second.empty()) {
      throw MeshError(fmt::format("{}: physical {} group {} has no name; every group must be named", source,
                                  dim == kSurfaceDim ? "surface" : "curve", tag));
    }
    groups.push_back({tag, name->second});
  }
  return groups;
}

/// Every node of the model by tag, checked to lie in the plane z = 0.
std::map<std::size_t, Point> model_nodes(const MshModel& model, const std::string& source) {
  double extent = 0.0;
  for (const auto& [tag, xyz] : model.nodes) extent = std::max({extent, std::abs(xyz[0]), std::abs(xyz[1])});
  std::map<std::size_t, Point> nodes;
  for (const auto& [tag, xyz] : model.nodes) {
    if (std::abs(xyz[2]) > kPlaneTolerance * extent) {
      throw MeshError(
          fmt::format("{}: node {} lies off the plane z = 0 (z = {}); expected a 2D "
                      "mesh in the xy plane",
                      source, tag, xyz[2]));
    }
    nodes.emplace_hint(nodes.end(), tag, Point{xyz[0], xyz[1]});
  }
  return nodes;
}

/// Collects cells and boundary edges by node tag, then numbers the nodes that cells use.
class MeshAssembler {
 public:
  explicit MeshAssembler(std::string source) : source_(std::move(source)) {}

  void add_cells(const MshEntity& entity, Index body) {
    for (const auto& [type, node_tags] : entity.elements) {
      const std::size_t corners = linear_node_count(type);
      for (std::size_t first = 0; first + corners <= node_tags.size(); first += corners) {
        cell_tags_.insert(cell_tags_.end(), node_tags.begin() + first, node_tags.begin() + first + corners);
        cell_sizes_.push_back(corners);
        cell_body_.push_back(body);
      }
    }
  }

  void add_edges(const MshEntity& entity, Index group) {
    const auto lines = entity.elements.find(kLine2);
    if (lines == entity.elements.end()) return;
    const std::vector<std::size_t>& node_tags = lines->second;
    for (std::size_t first = 0; first + 1 < node_tags.size(); first += 2) {
      edges_.push_back({node_tags[first], node_tags[first + 1], group});
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
        throw MeshError(
            fmt::format("{}: boundary group \"{}\" has a line on nodes of no cell", source_, boundaries[group]));
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
void check_surface_membership(const MshModel& model, const std::string& source) {
  for (const auto& [key, entity] : model.entities) {
    if (key.first == kSurfaceDim && !entity.elements.empty() && entity.groups.size() != 1) {
      throw MeshError(fmt::format("{}: surface {} with elements is in {} physical surface groups; expected exactly one",
                                  source, key.second, entity.groups.size()));
    }
  }
}

}  // namespace

void check_element_kind(int type, const ElementKind& kind, const std::string& source) {
  if (kind.dim == kVolumeDim) {
    throw MeshError(fmt::format("{}: holds 3D elements ({}); expected a 2D mesh", source, kind.name));
  }
  if (kind.order > 1) {
    throw MeshError(
        fmt::format("{}: holds second-order (curved) elements ({}); expected linear triangles and "
                    "quadrilaterals",
                    source, kind.name));
  }
  if (linear_node_count(type) == 0) {
    throw MeshError(fmt::format("{}: holds unsupported {}D elements ({}); expected triangles and quadrilaterals",
                                source, kind.dim, kind.name));
  }
}

Mesh mesh_from_model(const MshModel& model, const std::string& source) {
  const std::vector<NamedGroup> bodies = named_groups(model, kSurfaceDim, source);
  if (bodies.empty()) {
    throw MeshError(
        fmt::format("{}: has no physical surface groups; every body must be a named physical surface", source));
  }
  const std::vector<NamedGroup> boundaries = named_groups(model, kCurveDim, source);
  check_surface_membership(model, source);

  MeshAssembler assembler(source);
  std::vector<std::string> body_names, boundary_names;
  for (const NamedGroup& body : bodies) {
    for (const auto& [key, entity] : model.entities) {
      if (key.first == kSurfaceDim && entity.groups.count(body.tag) != 0) {
        assembler.add_cells(entity, static_cast<Index>(body_names.size()));
      }
    }
    body_names.push_back(body.name);
  }
  for (const NamedGroup& boundary : boundaries) {
    for (const auto& [key, entity] : model.entities) {
      if (key.first == kCurveDim && entity.groups.count(boundary.tag) != 0) {
        assembler.add_edges(entity, static_cast<Index>(boundary_names.size()));
      }
    }
    boundary_names.push_back(boundary.name);
  }
  Mesh mesh = assembler.finish(model_nodes(model, source), std::move(body_names), std::move(boundary_names));
  orient_cells_counter_clockwise(mesh, source);
  orient_boundary_edges(mesh, source);
  return mesh;
}

}  // namespace ddafrac::meshes::detail
