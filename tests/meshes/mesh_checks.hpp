#pragma once
// Independent measurements on a Mesh for the meshes tests (deliberately not the library's own
// helpers, so that a test does not check code against itself).

#include <algorithm>
#include <cmath>
#include <set>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::meshes::testing {

using common::kPi;
constexpr double kDegree = kPi / 180.0;

inline long index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto found = std::find(names.begin(), names.end(), name);
  return found == names.end() ? -1 : found - names.begin();
}

/// Shoelace area of cell c (positive when counter-clockwise).
inline double cell_area(const Mesh& mesh, std::size_t c) {
  double twice = 0.0;
  const std::size_t n = mesh.cell_size(c);
  for (std::size_t k = 0; k < n; ++k) {
    const Point& p = mesh.nodes[mesh.cell_begin(c)[k]];
    const Point& q = mesh.nodes[mesh.cell_begin(c)[(k + 1) % n]];
    twice += p.x * q.y - q.x * p.y;
  }
  return twice / 2;
}

inline double body_area(const Mesh& mesh, const std::string& body) {
  const long b = index_of(mesh.body_names, body);
  double area = 0.0;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (static_cast<long>(mesh.cell_body[c]) == b) area += cell_area(mesh, c);
  }
  return area;
}

inline std::size_t body_cells(const Mesh& mesh, const std::string& body) {
  const long b = index_of(mesh.body_names, body);
  return static_cast<std::size_t>(std::count_if(mesh.cell_body.begin(), mesh.cell_body.end(), [b](Index body_of_cell) {
    return static_cast<long>(body_of_cell) == b;
  }));
}

/// Smallest cell area divided by the square of its longest edge, over all cells: > 0 means
/// every cell is counter-clockwise with positive area.
inline double smallest_relative_area(const Mesh& mesh) {
  double smallest = HUGE_VAL;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    double longest = 0.0;
    const std::size_t n = mesh.cell_size(c);
    for (std::size_t k = 0; k < n; ++k) {
      const Point& p = mesh.nodes[mesh.cell_begin(c)[k]];
      const Point& q = mesh.nodes[mesh.cell_begin(c)[(k + 1) % n]];
      longest = std::max(longest, std::hypot(q.x - p.x, q.y - p.y));
    }
    smallest = std::min(smallest, cell_area(mesh, c) / (longest * longest));
  }
  return smallest;
}

/// Number of boundary edges that do not run a -> b in some cell.
inline std::size_t misoriented_boundary_edges(const Mesh& mesh) {
  std::set<std::pair<Index, Index>> directed;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    const std::size_t n = mesh.cell_size(c);
    for (std::size_t k = 0; k < n; ++k) {
      directed.emplace(mesh.cell_begin(c)[k], mesh.cell_begin(c)[(k + 1) % n]);
    }
  }
  return static_cast<std::size_t>(
      std::count_if(mesh.boundary_edges.begin(), mesh.boundary_edges.end(), [&](const BoundaryEdge& e) {
        return directed.count({e.a, e.b}) == 0;
      }));
}

inline std::vector<Point> group_nodes(const Mesh& mesh, const std::string& group) {
  const long g = index_of(mesh.boundary_names, group);
  std::set<Index> ids;
  for (const BoundaryEdge& e : mesh.boundary_edges) {
    if (static_cast<long>(e.group) == g) ids.insert({e.a, e.b});
  }
  std::vector<Point> points;
  for (Index i : ids) points.push_back(mesh.nodes[i]);
  return points;
}

/// Length and direction (rad, in [0, pi)) of a slot group, from its two most distant nodes.
struct SlotMeasure {
  double length = 0.0;
  double angle = 0.0;
};

inline SlotMeasure measure_slot(const Mesh& mesh, const std::string& group) {
  const std::vector<Point> points = group_nodes(mesh, group);
  SlotMeasure best;
  for (std::size_t i = 0; i < points.size(); ++i) {
    for (std::size_t j = i + 1; j < points.size(); ++j) {
      const double dx = points[j].x - points[i].x, dy = points[j].y - points[i].y;
      if (std::hypot(dx, dy) > best.length) {
        best.length = std::hypot(dx, dy);
        best.angle = std::fmod(std::atan2(dy, dx) + 2 * kPi, kPi);
      }
    }
  }
  return best;
}

/// Largest |r - R| and the angular half-width about direction `centre_angle` of a rim group.
inline double half_angle_about(const Mesh& mesh, const std::string& group, double centre_angle) {
  double half = 0.0;
  for (const Point& p : group_nodes(mesh, group)) {
    const double d = std::remainder(std::atan2(p.y, p.x) - centre_angle, 2 * kPi);
    half = std::max(half, std::abs(d));
  }
  return half;
}

/// Same nodes (within tol), cells, bodies and boundary groups.
inline bool same_mesh(const Mesh& a, const Mesh& b, double tol) {
  if (a.nodes.size() != b.nodes.size()) return false;
  for (std::size_t i = 0; i < a.nodes.size(); ++i) {
    if (std::abs(a.nodes[i].x - b.nodes[i].x) > tol || std::abs(a.nodes[i].y - b.nodes[i].y) > tol) {
      return false;
    }
  }
  auto edges = [](const Mesh& m) {
    std::vector<std::tuple<std::string, Index, Index>> list;
    for (const BoundaryEdge& e : m.boundary_edges) list.emplace_back(m.boundary_names[e.group], e.a, e.b);
    std::sort(list.begin(), list.end());
    return list;
  };
  return a.cell_offsets == b.cell_offsets && a.cell_nodes == b.cell_nodes && a.cell_body == b.cell_body &&
         a.body_names == b.body_names && edges(a) == edges(b);
}

}  // namespace ddafrac::meshes::testing
