#pragma once
// The blocky system: every mesh cell is a block with its own copy of its vertices (blocks move
// apart), plus per-block data in flat arrays (no pointer graphs; OpenMP loops walk indices).

#include <cmath>
#include <string>
#include <vector>

#include "ddafrac/dda/geometry.hpp"
#include "ddafrac/dda/types.hpp"
#include "ddafrac/meshes/mesh.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::dda {

/// Elastic data of one material, with the plane model already applied.
struct MaterialData {
  double density = 0.0;            // kg/m^3
  double young = 0.0;              // Pa
  double poisson = 0.0;            // -
  Mat3 elastic = Mat3::Zero();     // σ = elastic · (εx, εy, γxy)
  Mat3 compliance = Mat3::Zero();  // its inverse
};

/// E/(1-ν²)[[1,ν,0],[ν,1,0],[0,0,(1-ν)/2]] (plane stress) or the plane-strain matrix.
Mat3 elastic_matrix(double young, double poisson, scene::PlaneModel plane);

/// A material point held by a stiff spring at target(t) = start + velocity·t (fixed: v = 0).
struct Anchor {
  Index block = 0;
  double x = 0.0, y = 0.0;              // current position of the material point, m
  double x_start = 0.0, y_start = 0.0;  // target at t = 0, m
  double vx = 0.0, vy = 0.0;            // m/s
};

/// A constant force (N per unit thickness) on a material point of a block.
struct PointLoad {
  Index block = 0;
  double x = 0.0, y = 0.0;  // current position of the material point, m
  double fx = 0.0, fy = 0.0;
};

/// How a virtual joint failed: tensile if r1 > r2, shear otherwise.
enum class CrackType : std::uint8_t { None = 0, Tensile = 1, Shear = 2 };
const char* to_string(CrackType t);

/// An edge shared by two cells of the same body meshed with virtual joints: a bonded contact
/// until it breaks. Setting `broken` makes its contacts real joints from the next detection on
/// (the engine's fracture check does it and records the failure type; tests may do it directly).
struct Joint {
  Index block_a = 0, block_b = 0;        // block_a < block_b
  meshes::Index node_a = 0, node_b = 0;  // mesh nodes of the shared edge
  Index vertex_a = -1, vertex_b = -1;    // vertices of block_a at node_a / node_b (BlockSystem::vx)
  double length = 0.0;                   // m
  Index joint_set = 0;                   // index into Scene::joint_sets
  bool broken = false;
  CrackType failure = CrackType::None;  // set by the fracture check when it breaks
  // Damage D of a softening joint (JointSet::fracture_energy > 0), 0 ≤ D < 1 while intact: its
  // springs carry tension and shear with (1 − D) of their stiffness (docs/design.md §5).
  double damage = 0.0;
};

struct BlockSystem {
  // Vertices, compressed per block: block b owns vertex_offsets[b] .. vertex_offsets[b+1], CCW.
  std::vector<Index> vertex_offsets{0};
  std::vector<double> vx, vy;              // current vertex coordinates, m
  std::vector<meshes::Index> vertex_node;  // mesh node each vertex came from

  // Per block.
  std::vector<Index> body;       // index into Scene::bodies (-1: body not in the scene)
  std::vector<Index> mesh_body;  // index into Mesh::body_names
  std::vector<Index> material;   // index into materials
  std::vector<PolygonIntegrals> geometry;
  std::vector<double> mass;      // kg per unit thickness, fixed at t = 0 (ρ·initial area): the
                                 // mass matrix uses ρ_eff = mass/area so strain never changes it
  std::vector<double> min_edge;  // shortest edge of the block, m
  std::vector<Vec6> velocity;    // (u̇0, v̇0, ṙ0, ε̇x, ε̇y, γ̇xy)
  std::vector<Vec3> stress;      // (σxx, σyy, τxy), Pa, tension positive
  std::vector<Vec3> strain;      // accumulated (εx, εy, γxy)

  std::vector<MaterialData> materials;
  std::vector<Anchor> anchors;        // sorted by block
  std::vector<Index> anchor_offsets;  // per block, into anchors
  std::vector<PointLoad> loads;       // sorted by block
  std::vector<Index> load_offsets;    // per block, into loads
  std::vector<Joint> joints;          // sorted by (block_a, block_b)
  std::vector<Index> joint_offsets;   // per block, CSR into joint_of_block
  std::vector<Index> joint_of_block;

  double model_half_height = 0.0;  // half the initial y extent of the model, m

  std::size_t block_count() const { return geometry.size(); }
  std::size_t vertex_count() const { return vx.size(); }
  Index begin(std::size_t b) const { return vertex_offsets[b]; }
  Index end(std::size_t b) const { return vertex_offsets[b + 1]; }
  /// Midpoint of joint j's edge (block_a's side), m.
  meshes::Point joint_midpoint(const Joint& j) const {
    return {0.5 * (vx[j.vertex_a] + vx[j.vertex_b]), 0.5 * (vy[j.vertex_a] + vy[j.vertex_b])};
  }
  /// Unit tangent of joint j's edge (block_a's side), from node_a to node_b.
  meshes::Point joint_tangent(const Joint& j) const {
    const double tx = vx[j.vertex_b] - vx[j.vertex_a], ty = vy[j.vertex_b] - vy[j.vertex_a];
    const double l = std::hypot(tx, ty);
    return {tx / l, ty / l};
  }
};

/// Builds blocks from the mesh cells, materials from the scene, anchors for fixed and
/// prescribed bodies (every vertex of such a block), initial velocities, and the joint table
/// (edges shared by two cells of one body that has virtual joints, if bond_virtual_joints).
/// Extra point loads and anchors (tests, benchmarks) are added on top.
BlockSystem build_block_system(const scene::Scene& scene, const meshes::Mesh& mesh, bool bond_virtual_joints,
                               const std::vector<PointLoad>& extra_loads = {},
                               const std::vector<Anchor>& extra_anchors = {});

/// NodeTieGroups' entry of a vertex that no intact virtual joint at its node touches.
constexpr Index kNodeNotTied = -1;

/// The copies of each mesh node that intact virtual joints at the node hold together: around a
/// node, the blocks of its fan that a chain of intact joints at the node connects form one group
/// (all of the fan while it is intact; one group still while a crack only ends at the node; two
/// once a crack passes through it). Two copies of a group are tied (scene::IntactNodes::Tie).
struct NodeTieGroups {
  std::vector<Index> group;      // per vertex: its group's label (a vertex of it), or kNodeNotTied
  std::vector<Index> joint_set;  // per vertex: the joint set of an intact joint at it, or kNodeNotTied
  /// Whether vertices v and u (copies of one node) are tied.
  bool tied(Index v, Index u) const {
    return group[static_cast<std::size_t>(v)] != kNodeNotTied &&
           group[static_cast<std::size_t>(v)] == group[static_cast<std::size_t>(u)];
  }
};
NodeTieGroups node_tie_groups(const BlockSystem& blocks);

/// Recomputes area, centroid, moments and shortest edge of every block (parallel).
void update_block_geometry(BlockSystem& blocks);

/// Block containing the point (x, y), or -1.
Index find_block(const BlockSystem& blocks, double x, double y);

}  // namespace ddafrac::dda
