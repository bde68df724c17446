#pragma once
// The fan of six triangles around one node between two platens (tests of the copies of a shared
// mesh node: dda_energy, dda_node_ties), and a geometric measure of overlap.

#include <algorithm>
#include <cmath>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/dda/block_system.hpp"
#include "ddafrac/dda/contact_mechanics.hpp"
#include "support.hpp"

namespace ddafrac::dda::testing {

/// Six triangles around the node (0, 0) (a hexagon of circumradius r, one body with virtual
/// joints), between a fixed bottom platen and a top platen pressed down at `speed`.
struct Fan {
  double r = 0.01;     // m
  double speed = 2.0;  // m/s, top platen
  meshes::Mesh mesh;
  scene::Scene scene;
  Fan() {
    const double h = r * std::sqrt(3.0) / 2.0;
    for (meshes::Index k = 0; k < 6; ++k) {
      const double a = static_cast<double>(k) * 60.0 * common::kRadiansPerDegree;
      mesh.nodes.push_back({r * std::cos(a), r * std::sin(a)});
    }
    mesh.nodes.push_back({0.0, 0.0});
    mesh.body_names.push_back("fan");
    for (meshes::Index k = 0; k < 6; ++k) {
      mesh.cell_nodes.insert(mesh.cell_nodes.end(), {6, k, (k + 1) % 6});
      mesh.cell_offsets.push_back(static_cast<meshes::Index>(mesh.cell_nodes.size()));
      mesh.cell_body.push_back(0);
    }
    add_rectangle(mesh, "top", -0.5 * r, h, 0.5 * r, h + 0.005);
    add_rectangle(mesh, "bottom", -0.5 * r, -h - 0.005, 0.5 * r, -h);
    scene = basic_scene(scene::Mode::Dynamic, 1e-7, 1e11, {0.0, 0.0});
    scene::JointSet rock;
    rock.name = "rock";
    rock.friction_angle = 30.0 * common::kRadiansPerDegree;
    rock.cohesion = 5e6;
    rock.tensile_strength = 2e6;
    rock.normal_stiffness = 1e11;
    rock.shear_stiffness = 0.4e11;
    scene.joint_sets.push_back(rock);
    scene.joint_sets[0].friction_angle = 30.0 * common::kRadiansPerDegree;
    scene::Body fan = body("fan");
    fan.virtual_joints = 1;
    scene::Body top = body("top", scene::Motion::Prescribed);
    top.prescribed_velocity = {0.0, -speed};
    scene.bodies = {fan, top, body("bottom", scene::Motion::Fixed)};
  }
};

/// Deepest any vertex of block p lies inside block q (distance to q's nearest edge), m.
inline double deepest_vertex_inside(const BlockSystem& s, Index p, Index q) {
  double deepest = 0.0;
  for (Index v = s.begin(static_cast<std::size_t>(p)); v < s.end(static_cast<std::size_t>(p)); ++v) {
    double inside = 1e300;
    const Index q0 = s.begin(static_cast<std::size_t>(q)), q1 = s.end(static_cast<std::size_t>(q));
    for (Index a = q0; a < q1; ++a) {
      const Index b = a + 1 == q1 ? q0 : a + 1;
      inside = std::min(inside, -normal_gap(s.vx[v], s.vy[v], s.vx[a], s.vy[a], s.vx[b], s.vy[b]));
    }
    deepest = std::max(deepest, inside);
  }
  return deepest;
}

}  // namespace ddafrac::dda::testing
