#include "ddafrac/meshes/msh_io.hpp"

#include <gmsh.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

#include <fmt/format.h>

#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "gmsh_session.hpp"
#include "msh_model.hpp"
#include "msh_text.hpp"

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
        gmsh::model::mesh::addElementsByType(static_cast<int>(tag_of(b)), type, element_tags, node_tags);
      }
    }
  }
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.cell_size(c) != 3 && mesh.cell_size(c) != 4) {
      throw MeshError(
          fmt::format("{}: cell {} has {} nodes; msh files hold triangles and "
                      "quadrilaterals only",
                      file, c, mesh.cell_size(c)));
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
    gmsh::model::mesh::addElementsByType(static_cast<int>(tag_of(g)), kLine2, element_tags, node_tags);
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

/// A cell's corners, in order.
std::vector<Point> corners_of(const Mesh& mesh, std::size_t c) {
  std::vector<Point> corners;
  for (const Index* n = mesh.cell_begin(c); n != mesh.cell_begin(c) + mesh.cell_size(c); ++n)
    corners.push_back(mesh.nodes[static_cast<std::size_t>(*n)]);
  return corners;
}

/// Whether two convex cells share area (separating axes: the edge normals of both); cells that
/// only touch along an edge or at a corner, within `slack` (m), do not.
bool convex_cells_overlap(const std::vector<Point>& a, const std::vector<Point>& b, double slack) {
  for (const std::vector<Point>* polygon : {&a, &b}) {
    for (std::size_t k = 0; k < polygon->size(); ++k) {
      const Point& p = (*polygon)[k];
      const Point& q = (*polygon)[(k + 1) % polygon->size()];
      const double nx = q.y - p.y, ny = p.x - q.x;
      const double length = std::hypot(nx, ny);
      auto extent = [&](const std::vector<Point>& points) {
        double low = std::numeric_limits<double>::infinity(), high = -low;
        for (const Point& r : points) {
          const double s = (r.x * nx + r.y * ny) / length;
          low = std::min(low, s);
          high = std::max(high, s);
        }
        return std::pair{low, high};
      };
      const auto [a_low, a_high] = extent(a);
      const auto [b_low, b_high] = extent(b);
      if (a_high <= b_low + slack || b_high <= a_low + slack) return false;
    }
  }
  return true;
}

/// Refuses cells that overlap (within a body or between bodies): the DDA would start with
/// blocks inside each other, deeper than any contact it can see.
void refuse_overlapping_cells(const Mesh& mesh, const std::string& source) {
  const std::size_t n = mesh.cell_count();
  std::vector<std::vector<Point>> corners(n);
  std::vector<double> xmin(n), xmax(n), ymin(n), ymax(n);
  double extent = 0.0;
  for (std::size_t c = 0; c < n; ++c) {
    corners[c] = corners_of(mesh, c);
    xmin[c] = ymin[c] = std::numeric_limits<double>::infinity();
    xmax[c] = ymax[c] = -xmin[c];
    for (const Point& p : corners[c]) {
      xmin[c] = std::min(xmin[c], p.x);
      xmax[c] = std::max(xmax[c], p.x);
      ymin[c] = std::min(ymin[c], p.y);
      ymax[c] = std::max(ymax[c], p.y);
    }
    extent = std::max({extent, xmax[c] - xmin[c], ymax[c] - ymin[c]});
  }
  // Touching cells meet within rounding of their coordinates, not more.
  constexpr double kTouchingSlackPerCellSize = 1e-9;
  const double slack = kTouchingSlackPerCellSize * extent;
  std::vector<std::size_t> by_left(n);
  for (std::size_t c = 0; c < n; ++c) by_left[c] = c;
  std::sort(by_left.begin(), by_left.end(), [&](std::size_t a, std::size_t b) { return xmin[a] < xmin[b]; });
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t a = by_left[i];
    for (std::size_t j = i + 1; j < n && xmin[by_left[j]] < xmax[a] - slack; ++j) {
      const std::size_t b = by_left[j];
      if (ymin[b] >= ymax[a] - slack || ymin[a] >= ymax[b] - slack) continue;
      if (!convex_cells_overlap(corners[a], corners[b], slack)) continue;
      throw MeshError(fmt::format(
          "{}: two cells overlap near ({:.6g}, {:.6g}) m (bodies \"{}\" and \"{}\"): the blocks would start inside "
          "each other; fix the mesh or the placement of its bodies",
          source, 0.5 * (std::max(xmin[a], xmin[b]) + std::min(xmax[a], xmax[b])),
          0.5 * (std::max(ymin[a], ymin[b]) + std::min(ymax[a], ymax[b])),
          mesh.body_names[static_cast<std::size_t>(mesh.cell_body[a])],
          mesh.body_names[static_cast<std::size_t>(mesh.cell_body[b])]));
    }
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
  refuse_overlapping_cells(mesh, source);
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
