#include "cell_geometry.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::meshes::detail {

namespace {

using common::kPi;
constexpr double kDegreesPerRadian = 180.0 / kPi;

const Point& corner(const Mesh& mesh, std::size_t c, std::size_t k) {
  return mesh.nodes[mesh.cell_begin(c)[k % mesh.cell_size(c)]];
}

double angle_at(const Point& previous, const Point& at, const Point& next) {
  const double ax = previous.x - at.x, ay = previous.y - at.y;
  const double bx = next.x - at.x, by = next.y - at.y;
  return std::atan2(std::abs(ax * by - ay * bx), ax * bx + ay * by);
}

/// A cell's largest coordinate, as the scale against which an area counts as zero.
double cell_extent(const Mesh& mesh, std::size_t c) {
  double extent = 0.0;
  for (std::size_t k = 0; k < mesh.cell_size(c); ++k) {
    const Point& p = corner(mesh, c, k);
    const Point& q = corner(mesh, c, k + 1);
    extent = std::max(extent, std::hypot(q.x - p.x, q.y - p.y));
  }
  return extent;
}

}  // namespace

double signed_area(const Mesh& mesh, std::size_t c) {
  double twice_area = 0.0;
  for (std::size_t k = 0; k < mesh.cell_size(c); ++k) {
    const Point& p = corner(mesh, c, k);
    const Point& q = corner(mesh, c, k + 1);
    twice_area += p.x * q.y - q.x * p.y;
  }
  return 0.5 * twice_area;
}

double min_interior_angle_deg(const Mesh& mesh, std::size_t c) {
  const std::size_t n = mesh.cell_size(c);
  double smallest = kPi;
  for (std::size_t k = 0; k < n; ++k) {
    smallest = std::min(smallest, angle_at(corner(mesh, c, k + n - 1), corner(mesh, c, k), corner(mesh, c, k + 1)));
  }
  return smallest * kDegreesPerRadian;
}

void orient_cells_counter_clockwise(Mesh& mesh, const std::string& source) {
  constexpr double kRelativeZeroArea = 1e-12;  // of the squared longest edge
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const double area = signed_area(mesh, c);
    const double extent = cell_extent(mesh, c);
    if (std::abs(area) <= kRelativeZeroArea * extent * extent) {
      throw MeshError(fmt::format("{}: cell {} has zero area", source, c));
    }
    if (area < 0.0) {
      std::reverse(mesh.cell_nodes.begin() + mesh.cell_offsets[c], mesh.cell_nodes.begin() + mesh.cell_offsets[c + 1]);
    }
  }
}

void orient_boundary_edges(Mesh& mesh, const std::string& source) {
  std::set<std::pair<Index, Index>> directed_edges;  // (a, b) runs a -> b in some cell
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::size_t n = mesh.cell_size(c);
    for (std::size_t k = 0; k < n; ++k) {
      directed_edges.emplace(mesh.cell_begin(c)[k], mesh.cell_begin(c)[(k + 1) % n]);
    }
  }
  for (BoundaryEdge& edge : mesh.boundary_edges) {
    if (directed_edges.count({edge.a, edge.b}) != 0) continue;
    if (directed_edges.count({edge.b, edge.a}) == 0) {
      throw MeshError(fmt::format("{}: boundary edge ({}, {}) of group \"{}\" is no cell edge", source, edge.a, edge.b,
                                  mesh.boundary_names[edge.group]));
    }
    std::swap(edge.a, edge.b);
  }
}

}  // namespace ddafrac::meshes::detail
