#pragma once
// Hand-made scenes and meshes for the DDA tests (no scene parser, no gmsh).

#include <cmath>
#include <string>
#include <vector>

#include "ddafrac/meshes/mesh.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::dda::testing {

inline scene::Scene basic_scene(scene::Mode mode, double dt, double penalty, scene::Vec2 gravity) {
  scene::Scene s;
  s.name = "test";
  s.materials.push_back({"rock", 2000.0, 1e10, 0.2});
  scene::JointSet real;
  real.name = "real";
  real.friction_angle = 0.0;
  real.normal_stiffness = penalty;
  real.shear_stiffness = 0.4 * penalty;
  s.joint_sets.push_back(real);
  s.real_joints = 0;
  s.analysis.mode = mode;
  s.analysis.dt_max = dt;
  s.analysis.max_displacement_ratio = 0.01;
  s.analysis.penalty = penalty;
  s.analysis.end_time = 1.0;
  s.analysis.output_interval = 0.1;
  s.analysis.gravity = gravity;
  s.analysis.open_close_max = 8;
  return s;
}

inline scene::Body body(const std::string& name, scene::Motion motion = scene::Motion::Free, std::size_t material = 0) {
  scene::Body b;
  b.name = name;
  b.motion = motion;
  b.material = material;
  return b;
}

inline meshes::Index body_index(meshes::Mesh& m, const std::string& name) {
  for (std::size_t k = 0; k < m.body_names.size(); ++k)
    if (m.body_names[k] == name) return static_cast<meshes::Index>(k);
  m.body_names.push_back(name);
  return static_cast<meshes::Index>(m.body_names.size() - 1);
}

/// Appends a polygon cell (CCW points) of body `name`, with its own nodes.
inline void add_polygon(meshes::Mesh& m, const std::string& name, const std::vector<meshes::Point>& pts) {
  const meshes::Index b = body_index(m, name);
  for (const auto& p : pts) {
    m.cell_nodes.push_back(static_cast<meshes::Index>(m.nodes.size()));
    m.nodes.push_back(p);
  }
  m.cell_offsets.push_back(static_cast<meshes::Index>(m.cell_nodes.size()));
  m.cell_body.push_back(b);
}

inline void add_rectangle(meshes::Mesh& m, const std::string& name, double x0, double y0, double x1, double y1) {
  add_polygon(m, name, {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

/// A bar L x H of nx x ny squares, each split into two triangles (shared nodes, one body "rock");
/// node (i, j), at (L·i/nx, H·j/ny), is number j·(nx + 1) + i.
inline meshes::Mesh triangulated_bar(double length, double height, int nx, int ny) {
  meshes::Mesh m;
  m.body_names = {"rock"};
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.nodes.push_back({length * i / nx, height * j / ny});
  auto node = [&](int i, int j) { return static_cast<meshes::Index>(j * (nx + 1) + i); };
  m.cell_offsets = {0};
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      for (const auto& tri : {std::vector<meshes::Index>{node(i, j), node(i + 1, j), node(i + 1, j + 1)},
                              std::vector<meshes::Index>{node(i, j), node(i + 1, j + 1), node(i, j + 1)}}) {
        m.cell_nodes.insert(m.cell_nodes.end(), tri.begin(), tri.end());
        m.cell_offsets.push_back(static_cast<meshes::Index>(m.cell_nodes.size()));
        m.cell_body.push_back(0);
      }
    }
  return m;
}

}  // namespace ddafrac::dda::testing
