#include "ddafrac/meshes/msh_io.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <tuple>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "ddafrac/meshes/generate.hpp"
#include "gmsh_session.hpp"
#include "msh_model.hpp"
#include "msh_text.hpp"
#include "ddafrac/common/whole_file.hpp"

namespace ddafrac::meshes {

namespace {

using detail::kLine2;
using detail::kQuadrangle4;
using detail::kTriangle3;

constexpr double kMshFileVersion = 4.1;
constexpr Index kNoEntity = ~Index{0};

/// gmsh tags are 1-based: node i, cell c, body b and group g get tags i+1, c+1, b+1, g+1.
std::size_t tag_of(std::size_t index) { return index + 1; }

/// Each node is classified on the surface of the first cell that uses it.
void add_nodes(const Mesh& mesh) {
  std::vector<Index> entity_of(mesh.nodes.size(), kNoEntity);
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    for (std::size_t k = 0; k < mesh.cell_size(c); ++k) {
      Index& entity = entity_of[mesh.cell_begin(c)[k]];
      if (entity == kNoEntity) entity = mesh.cell_body[c];
    }
  }
  for (std::size_t b = 0; b < mesh.body_names.size(); ++b) {
    std::vector<std::size_t> tags;
    std::vector<double> coords;
    for (std::size_t i = 0; i < mesh.nodes.size(); ++i) {
      if (entity_of[i] != b) continue;
      tags.push_back(tag_of(i));
      coords.insert(coords.end(), {mesh.nodes[i].x, mesh.nodes[i].y, 0.0});
    }
    gmsh::model::mesh::addNodes(2, static_cast<int>(tag_of(b)), tags, coords);
  }
}

void add_cells(const Mesh& mesh, const std::string& file) {
  for (std::size_t b = 0; b < mesh.body_names.size(); ++b) {
    for (int type : {kTriangle3, kQuadrangle4}) {
      const std::size_t corners = type == kTriangle3 ? 3 : 4;
      std::vector<std::size_t> element_tags, node_tags;
      for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
        if (mesh.cell_body[c] != b || mesh.cell_size(c) != corners) continue;
        element_tags.push_back(tag_of(c));
        for (std::size_t k = 0; k < corners; ++k) node_tags.push_back(tag_of(mesh.cell_begin(c)[k]));
      }
      if (!element_tags.empty()) {
        gmsh::model::mesh::addElementsByType(static_cast<int>(tag_of(b)), type, element_tags,
                                             node_tags);
      }
    }
  }
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.cell_size(c) != 3 && mesh.cell_size(c) != 4) {
      throw MeshError(fmt::format("{}: cell {} has {} nodes; msh files hold triangles and "
                                  "quadrilaterals only", file, c, mesh.cell_size(c)));
    }
  }
}

void add_boundary_edges(const Mesh& mesh) {
  std::size_t next_tag = tag_of(mesh.cell_count());
  for (std::size_t g = 0; g < mesh.boundary_names.size(); ++g) {
    std::vector<std::size_t> element_tags, node_tags;
    for (const BoundaryEdge& edge : mesh.boundary_edges) {
      if (edge.group != g) continue;
      element_tags.push_back(next_tag++);
      node_tags.insert(node_tags.end(), {tag_of(edge.a), tag_of(edge.b)});
    }
    gmsh::model::mesh::addElementsByType(static_cast<int>(tag_of(g)), kLine2, element_tags,
                                         node_tags);
  }
}

void add_named_groups(int dim, const std::vector<std::string>& names) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    const int tag = static_cast<int>(tag_of(i));
    gmsh::model::addDiscreteEntity(dim, tag);
    gmsh::model::addPhysicalGroup(dim, {tag}, tag);
    gmsh::model::setPhysicalName(dim, tag, names[i]);
  }
}

/// Refuses two nodes of one body at the same place: the cells around them would not be joined
/// (no virtual joint), and the DDA would run with a cut the user never drew.
void refuse_coincident_nodes(const Mesh& mesh, const std::string& source) {
  struct Use {
    Index body;
    double x, y;
    Index node;
  };
  std::vector<Use> uses;
  uses.reserve(mesh.cell_nodes.size());
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    for (const Index* n = mesh.cell_begin(c); n != mesh.cell_begin(c) + mesh.cell_size(c); ++n)
      uses.push_back({mesh.cell_body[c], mesh.nodes[static_cast<std::size_t>(*n)].x,
                      mesh.nodes[static_cast<std::size_t>(*n)].y, *n});
  const auto place = [](const Use& u) { return std::tie(u.body, u.x, u.y); };
  std::sort(uses.begin(), uses.end(), [&](const Use& a, const Use& b) {
    return std::tie(a.body, a.x, a.y, a.node) < std::tie(b.body, b.x, b.y, b.node);
  });
  for (std::size_t k = 1; k < uses.size(); ++k) {
    const Use& a = uses[k - 1];
    const Use& b = uses[k];
    if (place(a) != place(b) || a.node == b.node) continue;
    throw MeshError(fmt::format(
        "{}: two nodes of body \"{}\" are at the same place ({:.9g}, {:.9g}) m, so the cells around them are not "
        "joined there; merge them (in gmsh: Geometry.AutoCoherence, or Tools > Options > Mesh > Remove duplicate "
        "nodes)",
        source, mesh.body_names[static_cast<std::size_t>(a.body)], a.x, a.y));
  }
}


}  // namespace

void write_msh(const Mesh& mesh, const std::filesystem::path& path) {
  const std::string file = path.string();
  detail::GmshSession session;
  detail::gmsh_call("writing " + file, [&] {
    gmsh::model::add("ddafrac");
    add_named_groups(2, mesh.body_names);
    add_named_groups(1, mesh.boundary_names);
    add_nodes(mesh);
    add_cells(mesh, file);
    add_boundary_edges(mesh);
    gmsh::option::setNumber("Mesh.MshFileVersion", kMshFileVersion);
    gmsh::option::setNumber("Mesh.Binary", 0);
    gmsh::option::setNumber("Mesh.SaveAll", 0);
    common::write_whole_file(path, [](const std::filesystem::path& temporary) {
      gmsh::write(temporary.string());
      const std::string error = detail::gmsh_last_error();
      if (!error.empty()) throw MeshError(error);
    });
  });
}

Mesh parse_msh(std::string_view text, const std::filesystem::path& file_name) {
  const std::string source = file_name.string();
  Mesh mesh = detail::mesh_from_model(detail::parse_msh_text(text, source), source);
  refuse_coincident_nodes(mesh, source);
  return mesh;
}

Mesh read_msh(const std::filesystem::path& path) {
  const std::string file = path.string();
  std::error_code error_code;
  if (!std::filesystem::is_regular_file(path, error_code)) {
    throw MeshError(file + ": no such file");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw MeshError(file + ": cannot open it");
  const std::string text{std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  if (in.bad()) throw MeshError(file + ": cannot read it");
  return parse_msh(text, path);
}

}  // namespace ddafrac::meshes
