#include "ddafrac/meshes/edge_lines.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "quality_detail.hpp"

namespace ddafrac::meshes {

namespace {

using Edge = std::pair<Index, Index>;  // node indices, first < second

/// Interior edges of the body: those that two of its cells share.
std::vector<Edge> interior_edges(const Mesh& mesh, long body) {
  std::map<Edge, int> cells_per_edge;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (static_cast<long>(mesh.cell_body[c]) != body) continue;
    const Index* nodes = mesh.cell_begin(c);
    const std::size_t n = mesh.cell_size(c);
    for (std::size_t k = 0; k < n; ++k) {
      const Index a = nodes[k], b = nodes[(k + 1) % n];
      ++cells_per_edge[{std::min(a, b), std::max(a, b)}];
    }
  }
  std::vector<Edge> edges;
  for (const auto& [edge, cells] : cells_per_edge) {
    if (cells == 2) edges.push_back(edge);
  }
  return edges;
}

class EdgeLines {
 public:
  EdgeLines(const Mesh& mesh, std::vector<Edge> edges, double max_turn_deg)
      : mesh_(mesh), edges_(std::move(edges)), min_cos_(std::cos(max_turn_deg * common::kRadiansPerDegree)),
        node_edges_(mesh.nodes.size()) {
    for (std::size_t e = 0; e < edges_.size(); ++e) {
      node_edges_[edges_[e].first].push_back(e);
      node_edges_[edges_[e].second].push_back(e);
    }
  }

  double longest() const {
    double best = 0.0;
    for (const auto& [a, b] : edges_) {
      best = std::max(best, length(a, b) + run_on(a, b) + run_on(b, a));
    }
    return best;
  }

 private:
  double length(Index a, Index b) const { return std::hypot(dx(a, b), dy(a, b)); }
  double dx(Index a, Index b) const { return mesh_.nodes[b].x - mesh_.nodes[a].x; }
  double dy(Index a, Index b) const { return mesh_.nodes[b].y - mesh_.nodes[a].y; }

  /// Length of the straight line continuing edge from -> to beyond `to`. The turn limit keeps a
  /// line from closing on itself before it has turned through a full circle, and the step count
  /// stops it there.
  double run_on(Index from, Index to) const {
    double total = 0.0;
    for (std::size_t steps = 0; steps < edges_.size(); ++steps) {
      const double ux = dx(from, to) / length(from, to), uy = dy(from, to) / length(from, to);
      double best_cos = min_cos_;
      Index next = to;
      for (const std::size_t e : node_edges_[to]) {
        const Index other = edges_[e].first == to ? edges_[e].second : edges_[e].first;
        if (other == from) continue;
        const double cos_turn = (ux * dx(to, other) + uy * dy(to, other)) / length(to, other);
        if (cos_turn >= best_cos) {
          best_cos = cos_turn;
          next = other;
        }
      }
      if (next == to) break;
      total += length(to, next);
      from = std::exchange(to, next);
    }
    return total;
  }

  const Mesh& mesh_;
  std::vector<Edge> edges_;
  double min_cos_;
  std::vector<std::vector<std::size_t>> node_edges_;
};

}  // namespace

double longest_straight_edge_line(const Mesh& mesh, const std::string& body, double max_turn_deg) {
  const long index = detail::body_index(mesh, body);
  if (index < 0) throw MeshError("longest_straight_edge_line: the mesh has no body named \"" + body + "\"");
  return EdgeLines(mesh, interior_edges(mesh, index), max_turn_deg).longest();
}

}  // namespace ddafrac::meshes
