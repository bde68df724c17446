#pragma once
// Test meshes of a disc built without gmsh: concentric rings of triangles (ring i has 6i
// nodes, every ring has a node at the top), optionally split into quadrilaterals. The rim
// edges within `load_half_angle` of the top/bottom points form the groups "load_top" and
// "load_bottom", the others "rim". Used while the gmsh-based generator is unavailable and to
// have meshes whose loaded-arc ends are nodes for any refinement.

#include <array>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::test {

constexpr double test_pi = ddafrac::common::kPi;

inline meshes::Mesh ring_disc(double radius, int rings, double load_half_angle) {
  meshes::Mesh m;
  m.body_names = {"disc"};
  m.boundary_names = {"rim", "load_top", "load_bottom"};
  std::vector<std::vector<meshes::Index>> ring(static_cast<std::size_t>(rings) + 1);
  m.nodes.push_back({0.0, 0.0});
  ring[0] = {0};
  for (int i = 1; i <= rings; ++i) {
    const int n = 6 * i;
    for (int j = 0; j < n; ++j) {
      const double a = 0.5 * test_pi + 2.0 * test_pi * j / n;
      ring[static_cast<std::size_t>(i)].push_back(static_cast<meshes::Index>(m.nodes.size()));
      m.nodes.push_back({radius * i / rings * std::cos(a), radius * i / rings * std::sin(a)});
    }
  }
  auto add_cell = [&m](std::vector<meshes::Index> nodes) {
    for (auto n : nodes) m.cell_nodes.push_back(n);
    m.cell_offsets.push_back(static_cast<meshes::Index>(m.cell_nodes.size()));
    m.cell_body.push_back(0);
  };
  for (int i = 1; i <= rings; ++i) {
    const auto& in = ring[static_cast<std::size_t>(i - 1)];
    const auto& out = ring[static_cast<std::size_t>(i)];
    const std::size_t ni = in.size(), no = out.size();
    std::size_t a = 0, b = 0;
    while (a < ni || b < no) {
      const double next_in = ni == 1 ? 1e9 : static_cast<double>(a + 1) / ni;
      const double next_out = static_cast<double>(b + 1) / no;
      if (b < no && (a >= ni || ni == 1 || next_out <= next_in)) {
        add_cell({in[a % ni], out[b % no], out[(b + 1) % no]});
        ++b;
      } else {
        add_cell({in[a % ni], out[b % no], in[(a + 1) % ni]});
        ++a;
      }
      if (ni == 1 && b == no) break;
    }
  }
  const auto& rim = ring.back();
  for (std::size_t j = 0; j < rim.size(); ++j) {
    const auto a = rim[j], b = rim[(j + 1) % rim.size()];
    const double mx = 0.5 * (m.nodes[a].x + m.nodes[b].x), my = 0.5 * (m.nodes[a].y + m.nodes[b].y);
    const double from_top = std::abs(std::atan2(mx, my));  // angle from +y
    meshes::Index group = 0;
    if (from_top < load_half_angle) group = 1;
    if (test_pi - from_top < load_half_angle) group = 2;
    m.boundary_edges.push_back({a, b, group});
  }
  return m;
}

/// Splits every triangle into three quadrilaterals (centroid + edge midpoints); midpoints of
/// rim edges are put on the circle of radius `radius` about the origin.
inline meshes::Mesh split_into_quads(const meshes::Mesh& tri, double radius) {
  meshes::Mesh m;
  m.nodes = tri.nodes;
  m.body_names = tri.body_names;
  m.boundary_names = tri.boundary_names;
  std::map<std::pair<meshes::Index, meshes::Index>, meshes::Index> mid;
  std::map<std::pair<meshes::Index, meshes::Index>, meshes::Index> boundary_group;
  for (const auto& e : tri.boundary_edges) boundary_group[{std::min(e.a, e.b), std::max(e.a, e.b)}] = e.group;
  auto midpoint = [&](meshes::Index a, meshes::Index b) {
    const auto key = std::make_pair(std::min(a, b), std::max(a, b));
    const auto it = mid.find(key);
    if (it != mid.end()) return it->second;
    meshes::Point p{0.5 * (m.nodes[a].x + m.nodes[b].x), 0.5 * (m.nodes[a].y + m.nodes[b].y)};
    if (boundary_group.count(key)) {
      const double r = std::hypot(p.x, p.y);
      p = {p.x * radius / r, p.y * radius / r};
    }
    const auto id = static_cast<meshes::Index>(m.nodes.size());
    m.nodes.push_back(p);
    mid[key] = id;
    return id;
  };
  for (std::size_t c = 0; c < tri.cell_count(); ++c) {
    const meshes::Index* n = tri.cell_begin(c);
    const meshes::Index ab = midpoint(n[0], n[1]), bc = midpoint(n[1], n[2]), ca = midpoint(n[2], n[0]);
    const auto g = static_cast<meshes::Index>(m.nodes.size());
    m.nodes.push_back({(tri.nodes[n[0]].x + tri.nodes[n[1]].x + tri.nodes[n[2]].x) / 3.0,
                       (tri.nodes[n[0]].y + tri.nodes[n[1]].y + tri.nodes[n[2]].y) / 3.0});
    for (const auto& q : {std::array<meshes::Index, 4>{n[0], ab, g, ca}, std::array<meshes::Index, 4>{n[1], bc, g, ab},
                          std::array<meshes::Index, 4>{n[2], ca, g, bc}}) {
      for (auto v : q) m.cell_nodes.push_back(v);
      m.cell_offsets.push_back(static_cast<meshes::Index>(m.cell_nodes.size()));
      m.cell_body.push_back(tri.cell_body[c]);
    }
  }
  for (const auto& e : tri.boundary_edges) {
    const auto c = midpoint(e.a, e.b);
    m.boundary_edges.push_back({e.a, c, e.group});
    m.boundary_edges.push_back({c, e.b, e.group});
  }
  return m;
}

}  // namespace ddafrac::test
