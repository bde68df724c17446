#include "ddafrac/dda/block_system.hpp"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include "ddafrac/common/polygon.hpp"

namespace ddafrac::dda {

const char* to_string(CrackType t) {
  switch (t) {
    case CrackType::None: return "none";
    case CrackType::Tensile: return "tensile";
    case CrackType::Shear: return "shear";
  }
  return "?";
}

Mat3 elastic_matrix(double young, double poisson, scene::PlaneModel plane) {
  Mat3 e = Mat3::Zero();
  const double nu = poisson;
  if (plane == scene::PlaneModel::Stress) {
    const double c = young / (1.0 - nu * nu);
    e << c, c * nu, 0.0, c * nu, c, 0.0, 0.0, 0.0, c * 0.5 * (1.0 - nu);
  } else {
    const double c = young / ((1.0 + nu) * (1.0 - 2.0 * nu));
    e << c * (1.0 - nu), c * nu, 0.0, c * nu, c * (1.0 - nu), 0.0, 0.0, 0.0, c * 0.5 * (1.0 - 2.0 * nu);
  }
  return e;
}

namespace {

template <class T>
std::vector<Index> offsets_by_block(const std::vector<T>& items, std::size_t blocks) {
  std::vector<Index> off(blocks + 1, 0);
  for (const T& it : items) ++off[static_cast<std::size_t>(it.block) + 1];
  for (std::size_t b = 0; b < blocks; ++b) off[b + 1] += off[b];
  return off;
}

}  // namespace

void update_block_geometry(BlockSystem& blocks) {
  const auto n = static_cast<std::int64_t>(blocks.block_count());
#pragma omp parallel for schedule(static)
  for (std::int64_t b = 0; b < n; ++b) {
    const auto bb = static_cast<std::size_t>(b);
    const Index v0 = blocks.begin(bb);
    const Index nv = blocks.end(bb) - v0;
    blocks.geometry[bb] = polygon_integrals(blocks.vx.data() + v0, blocks.vy.data() + v0, static_cast<std::size_t>(nv));
    double m = INFINITY;
    for (Index k = 0; k < nv; ++k) {
      const Index a = v0 + k;
      const Index c = v0 + (k + 1) % nv;
      m = std::min(m, std::hypot(blocks.vx[static_cast<std::size_t>(c)] - blocks.vx[static_cast<std::size_t>(a)],
                                 blocks.vy[static_cast<std::size_t>(c)] - blocks.vy[static_cast<std::size_t>(a)]));
    }
    blocks.min_edge[bb] = m;
  }
}

BlockSystem build_block_system(const scene::Scene& scene, const meshes::Mesh& mesh, bool bond_virtual_joints,
                               const std::vector<PointLoad>& extra_loads, const std::vector<Anchor>& extra_anchors) {
  if (scene.materials.empty()) throw std::invalid_argument("the scene defines no material");
  BlockSystem s;
  const std::size_t nb = mesh.cell_count();
  for (const auto& m : scene.materials) {
    MaterialData d;
    d.density = m.density;
    d.young = m.young;
    d.poisson = m.poisson;
    d.elastic = elastic_matrix(m.young, m.poisson, scene.analysis.plane);
    d.compliance = d.elastic.inverse();
    s.materials.push_back(d);
  }
  // Mesh body -> scene body by name.
  std::vector<Index> scene_body_of_mesh_body(mesh.body_names.size(), -1);
  for (std::size_t mb = 0; mb < mesh.body_names.size(); ++mb)
    for (std::size_t sb = 0; sb < scene.bodies.size(); ++sb)
      if (scene.bodies[sb].name == mesh.body_names[mb]) scene_body_of_mesh_body[mb] = static_cast<Index>(sb);

  s.vertex_offsets.assign(1, 0);
  s.body.resize(nb);
  s.mesh_body.resize(nb);
  s.material.resize(nb);
  s.velocity.assign(nb, Vec6::Zero());
  s.stress.assign(nb, Vec3::Zero());
  s.strain.assign(nb, Vec3::Zero());
  double ymin = INFINITY, ymax = -INFINITY;
  for (std::size_t c = 0; c < nb; ++c) {
    const std::size_t n = mesh.cell_size(c);
    const meshes::Index* nodes = mesh.cell_begin(c);
    // Orientation guard: blocks are stored counter-clockwise whatever the input says.
    double a2 = 0.0;
    for (std::size_t k = 0; k < n; ++k) {
      const auto& p = mesh.nodes[nodes[k]];
      const auto& q = mesh.nodes[nodes[(k + 1) % n]];
      a2 += p.x * q.y - q.x * p.y;
    }
    for (std::size_t k = 0; k < n; ++k) {
      const meshes::Index node = a2 >= 0.0 ? nodes[k] : nodes[n - 1 - k];
      s.vx.push_back(mesh.nodes[node].x);
      s.vy.push_back(mesh.nodes[node].y);
      s.vertex_node.push_back(node);
      ymin = std::min(ymin, mesh.nodes[node].y);
      ymax = std::max(ymax, mesh.nodes[node].y);
    }
    s.vertex_offsets.push_back(static_cast<Index>(s.vx.size()));
    const meshes::Index mb = mesh.cell_body[c];
    s.mesh_body[c] = static_cast<Index>(mb);
    const Index sb = mb < scene_body_of_mesh_body.size() ? scene_body_of_mesh_body[mb] : -1;
    s.body[c] = sb;
    s.material[c] = 0;
    if (sb >= 0) {
      const auto& body = scene.bodies[static_cast<std::size_t>(sb)];
      if (body.material >= scene.materials.size())
        throw std::invalid_argument("body '" + body.name + "' refers to a missing material");
      s.material[c] = static_cast<Index>(body.material);
      s.velocity[c][kU] = body.initial_velocity[0];
      s.velocity[c][kV] = body.initial_velocity[1];
    }
  }
  s.model_half_height = nb > 0 ? 0.5 * (ymax - ymin) : 0.0;
  s.geometry.resize(nb);
  s.min_edge.resize(nb);
  update_block_geometry(s);
  s.mass.resize(nb);
  for (std::size_t c = 0; c < nb; ++c)
    s.mass[c] = s.materials[static_cast<std::size_t>(s.material[c])].density * s.geometry[c].area;

  // Anchors: every vertex of a fixed or prescribed block.
  for (std::size_t c = 0; c < nb; ++c) {
    if (s.body[c] < 0) continue;
    const auto& body = scene.bodies[static_cast<std::size_t>(s.body[c])];
    if (body.motion == scene::Motion::Free) continue;
    const double vx = body.motion == scene::Motion::Prescribed ? body.prescribed_velocity[0] : 0.0;
    const double vy = body.motion == scene::Motion::Prescribed ? body.prescribed_velocity[1] : 0.0;
    s.velocity[c] = Vec6::Zero();
    s.velocity[c][kU] = vx;
    s.velocity[c][kV] = vy;
    for (Index v = s.begin(c); v < s.end(c); ++v) {
      Anchor a;
      a.block = static_cast<Index>(c);
      a.x = a.x_start = s.vx[static_cast<std::size_t>(v)];
      a.y = a.y_start = s.vy[static_cast<std::size_t>(v)];
      a.vx = vx;
      a.vy = vy;
      s.anchors.push_back(a);
    }
  }
  for (const Anchor& a : extra_anchors) s.anchors.push_back(a);
  std::stable_sort(s.anchors.begin(), s.anchors.end(),
                   [](const Anchor& p, const Anchor& q) { return p.block < q.block; });
  s.anchor_offsets = offsets_by_block(s.anchors, nb);
  s.loads = extra_loads;
  std::stable_sort(s.loads.begin(), s.loads.end(),
                   [](const PointLoad& p, const PointLoad& q) { return p.block < q.block; });
  s.load_offsets = offsets_by_block(s.loads, nb);

  // Joints: edges shared by two cells of one body meshed with virtual joints.
  if (bond_virtual_joints) {
    struct EdgeRef {
      meshes::Index lo, hi;
      Index block;
    };
    std::vector<EdgeRef> edges;
    for (std::size_t c = 0; c < nb; ++c) {
      if (s.body[c] < 0) continue;
      if (!scene.bodies[static_cast<std::size_t>(s.body[c])].virtual_joints) continue;
      const Index v0 = s.begin(c);
      const Index nv = s.end(c) - v0;
      for (Index k = 0; k < nv; ++k) {
        const meshes::Index a = s.vertex_node[static_cast<std::size_t>(v0 + k)];
        const meshes::Index b = s.vertex_node[static_cast<std::size_t>(v0 + (k + 1) % nv)];
        edges.push_back({std::min(a, b), std::max(a, b), static_cast<Index>(c)});
      }
    }
    std::sort(edges.begin(), edges.end(), [](const EdgeRef& p, const EdgeRef& q) {
      return std::tie(p.lo, p.hi, p.block) < std::tie(q.lo, q.hi, q.block);
    });
    for (std::size_t k = 0; k + 1 < edges.size(); ++k) {
      const EdgeRef& p = edges[k];
      const EdgeRef& q = edges[k + 1];
      if (p.lo != q.lo || p.hi != q.hi) continue;
      if (s.mesh_body[static_cast<std::size_t>(p.block)] != s.mesh_body[static_cast<std::size_t>(q.block)]) continue;
      Joint j;
      j.block_a = std::min(p.block, q.block);
      j.block_b = std::max(p.block, q.block);
      j.node_a = p.lo;
      j.node_b = p.hi;
      j.length = std::hypot(mesh.nodes[p.hi].x - mesh.nodes[p.lo].x, mesh.nodes[p.hi].y - mesh.nodes[p.lo].y);
      j.joint_set = static_cast<Index>(
          *scene.bodies[static_cast<std::size_t>(s.body[static_cast<std::size_t>(p.block)])].virtual_joints);
      s.joints.push_back(j);
    }
    std::sort(s.joints.begin(), s.joints.end(), [](const Joint& p, const Joint& q) {
      return std::tie(p.block_a, p.block_b, p.node_a, p.node_b) < std::tie(q.block_a, q.block_b, q.node_a, q.node_b);
    });
    for (Joint& j : s.joints)
      for (Index v = s.begin(static_cast<std::size_t>(j.block_a)); v < s.end(static_cast<std::size_t>(j.block_a));
           ++v) {
        if (s.vertex_node[static_cast<std::size_t>(v)] == j.node_a) j.vertex_a = v;
        if (s.vertex_node[static_cast<std::size_t>(v)] == j.node_b) j.vertex_b = v;
      }
  }
  s.joint_offsets.assign(nb + 1, 0);
  for (const Joint& j : s.joints) {
    ++s.joint_offsets[static_cast<std::size_t>(j.block_a) + 1];
    ++s.joint_offsets[static_cast<std::size_t>(j.block_b) + 1];
  }
  for (std::size_t b = 0; b < nb; ++b) s.joint_offsets[b + 1] += s.joint_offsets[b];
  s.joint_of_block.assign(static_cast<std::size_t>(s.joint_offsets[nb]), 0);
  {
    std::vector<Index> fill(s.joint_offsets.begin(), s.joint_offsets.end() - 1);
    for (std::size_t k = 0; k < s.joints.size(); ++k) {
      const Joint& j = s.joints[k];
      s.joint_of_block[static_cast<std::size_t>(fill[static_cast<std::size_t>(j.block_a)]++)] = static_cast<Index>(k);
      s.joint_of_block[static_cast<std::size_t>(fill[static_cast<std::size_t>(j.block_b)]++)] = static_cast<Index>(k);
    }
  }
  return s;
}

NodeTieGroups node_tie_groups(const BlockSystem& blocks) {
  const std::size_t nv = blocks.vertex_count();
  std::vector<Index> parent(nv);
  std::iota(parent.begin(), parent.end(), Index{0});
  const auto root = [&](Index v) {
    while (parent[static_cast<std::size_t>(v)] != v)
      v = parent[static_cast<std::size_t>(v)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(v)])];
    return v;
  };
  const auto copy_in = [&](Index block, meshes::Index node) {
    for (Index v = blocks.begin(static_cast<std::size_t>(block)); v < blocks.end(static_cast<std::size_t>(block)); ++v)
      if (blocks.vertex_node[static_cast<std::size_t>(v)] == node) return v;
    return kNodeNotTied;
  };
  NodeTieGroups g;
  g.joint_set.assign(nv, kNodeNotTied);
  // Serial, in joint order, the smaller root kept: the labels do not depend on the thread count.
  for (const Joint& j : blocks.joints) {
    if (j.broken) continue;
    for (const auto& [va, node] : {std::pair{j.vertex_a, j.node_a}, std::pair{j.vertex_b, j.node_b}}) {
      const Index vb = copy_in(j.block_b, node);
      const Index ra = root(va), rb = root(vb);
      parent[static_cast<std::size_t>(std::max(ra, rb))] = std::min(ra, rb);
      g.joint_set[static_cast<std::size_t>(va)] = g.joint_set[static_cast<std::size_t>(vb)] = j.joint_set;
    }
  }
  g.group.resize(nv);
  for (std::size_t v = 0; v < nv; ++v)
    g.group[v] = g.joint_set[v] == kNodeNotTied ? kNodeNotTied : root(static_cast<Index>(v));
  return g;
}

Index find_block(const BlockSystem& blocks, double x, double y) {
  for (std::size_t b = 0; b < blocks.block_count(); ++b) {
    const auto v0 = static_cast<std::size_t>(blocks.begin(b));
    const auto n = static_cast<std::size_t>(blocks.end(b) - blocks.begin(b));
    if (common::inside_polygon(&blocks.vx[v0], &blocks.vy[v0], n, x, y)) return static_cast<Index>(b);
  }
  return -1;
}

}  // namespace ddafrac::dda
