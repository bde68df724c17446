#include "ddafrac/dda/synthetic.hpp"

#include <algorithm>
#include <cmath>

#include "ddafrac/common/angles.hpp"

namespace ddafrac::dda {

namespace {
using common::kPi;
}

meshes::Mesh make_ring_disc_mesh(double diameter, int target_blocks, double plate_width, double plate_height) {
  meshes::Mesh m;
  m.body_names = {"disc"};
  const int n = std::max(1, static_cast<int>(std::lround(std::sqrt(target_blocks / 6.0))));
  const double r = 0.5 * diameter;
  std::vector<meshes::Index> ring_start;  // first node of ring k
  m.nodes.push_back({0.0, 0.0});
  ring_start.push_back(0);
  for (int k = 1; k <= n; ++k) {
    ring_start.push_back(static_cast<meshes::Index>(m.nodes.size()));
    const int count = 6 * k;
    for (int j = 0; j < count; ++j) {
      const double a = 2.0 * kPi * j / count;
      m.nodes.push_back({r * k / n * std::cos(a), r * k / n * std::sin(a)});
    }
  }
  auto tri = [&](meshes::Index a, meshes::Index b, meshes::Index c) {
    m.cell_nodes.insert(m.cell_nodes.end(), {a, b, c});
    m.cell_offsets.push_back(static_cast<meshes::Index>(m.cell_nodes.size()));
    m.cell_body.push_back(0);
  };
  for (int j = 0; j < 6; ++j) tri(0, ring_start[1] + j, ring_start[1] + (j + 1) % 6);
  for (int k = 2; k <= n; ++k) {
    const int mi = 6 * (k - 1), mo = 6 * k;
    const meshes::Index in0 = ring_start[k - 1], out0 = ring_start[k];
    int i = 0, j = 0;
    while (i < mi || j < mo) {
      const double ai = static_cast<double>(i + 1) / mi, ao = static_cast<double>(j + 1) / mo;
      if (i == mi || (j < mo && ao <= ai)) {
        tri(in0 + i % mi, out0 + j % mo, out0 + (j + 1) % mo);
        ++j;
      } else {
        tri(in0 + i % mi, out0 + j % mo, in0 + (i + 1) % mi);
        ++i;
      }
    }
  }
  if (plate_height > 0.0) {
    double ymin = 0.0;
    for (const auto& p : m.nodes) ymin = std::min(ymin, p.y);
    m.body_names.push_back("plate");
    const auto b = static_cast<meshes::Index>(m.nodes.size());
    const double w = 0.5 * plate_width;
    m.nodes.push_back({-w, ymin - plate_height});
    m.nodes.push_back({w, ymin - plate_height});
    m.nodes.push_back({w, ymin});
    m.nodes.push_back({-w, ymin});
    m.cell_nodes.insert(m.cell_nodes.end(), {b, b + 1, b + 2, b + 3});
    m.cell_offsets.push_back(static_cast<meshes::Index>(m.cell_nodes.size()));
    m.cell_body.push_back(1);
  }
  return m;
}

scene::Scene make_impact_scene(double v0, double end_time) {
  scene::Scene s;
  s.name = "synthetic-impact";
  s.description = "glued ring-triangulated disc impacting a fixed plate (benchmark)";
  s.materials.push_back({"rock", 2050.0, 10.53e9, 0.12});
  const double deg = kPi / 180.0;
  const double kn = 0.35e9;
  const double ks = scene::kDefaultShearToNormalStiffness * kn;  // as a scene file that gives none
  s.joint_sets.push_back({"virtual", 38.5 * deg, 8.29e6, 7.86e6, kn, ks});
  s.joint_sets.push_back({"real", 20.0 * deg, 1e6, 1e-5 * 1e6, kn, ks});
  s.real_joints = 1;
  scene::Body disc;
  disc.name = "disc";
  disc.virtual_joints = 0;
  disc.initial_velocity = {0.0, -v0};
  scene::Body plate;
  plate.name = "plate";
  plate.role = scene::Role::Plate;
  plate.motion = scene::Motion::Fixed;
  s.bodies = {disc, plate};
  s.analysis.mode = scene::Mode::Dynamic;
  s.analysis.plane = scene::PlaneModel::Stress;
  s.analysis.dt_max = 1e-7;
  s.analysis.max_displacement_ratio = 1e-4;
  s.analysis.penalty = kn;
  s.analysis.end_time = end_time;
  s.analysis.output_interval = end_time;
  s.analysis.gravity = {0.0, -9.81};
  s.analysis.open_close_max = 6;
  return s;
}

}  // namespace ddafrac::dda
