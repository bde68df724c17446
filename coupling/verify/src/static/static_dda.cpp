// The static DDA twin run. Both models carry the same load: the FEM as a boundary pressure, the
// DDA as the consistent nodal forces of the same pressure on its rim vertices (PointLoad). The
// DDA's rigid-body modes are removed by four anchors at (±R/2, 0), (0, ±R/2) whose targets follow
// the deformation, so that they resist rigid-body motion only: the loads are self-equilibrated
// and symmetric, so in the converged state the anchors carry round-off (their largest force is
// reported).

#include "static/static_dda.hpp"

#include <fmt/core.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/common/polygon.hpp"
#include "ddafrac/common/stopwatch.hpp"
#include "ddafrac/common/thread_scope.hpp"
#include "ddafrac/coupling/dda_twin.hpp"
#include "ddafrac/dda/drive.hpp"
#include "ddafrac/meshes/generate.hpp"

namespace ddafrac::coupling {

using common::kPi;

namespace {

using Clock = std::chrono::steady_clock;
using common::seconds_since;

/// The bonded twin of the disc alone, in static mode.
DdaTwin static_twin(const scene::Scene& scene, double kn_over_young) {
  DdaTwin twin = bonded_dda_twin(scene, kn_over_young);
  scene::Scene& s = twin.scene;
  s.bodies.erase(std::remove_if(s.bodies.begin(), s.bodies.end(),
                                [](const scene::Body& b) { return b.role != scene::Role::Disc; }),
                 s.bodies.end());
  s.analysis.mode = scene::Mode::Static;
  s.analysis.dt_max = kStaticTwinDt;
  s.analysis.search_distance_factor = kStaticTwinSearchDistanceFactor;
  s.gauges.clear();
  return twin;
}

std::optional<std::size_t> cell_containing(const meshes::Mesh& m, double x, double y) {
  std::vector<double> cx, cy;
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    cx.clear();
    cy.clear();
    for (const meshes::Index* n = m.cell_begin(c); n != m.cell_begin(c) + m.cell_size(c); ++n) {
      cx.push_back(m.nodes[*n].x);
      cy.push_back(m.nodes[*n].y);
    }
    if (common::inside_polygon(cx.data(), cy.data(), cx.size(), x, y)) return c;
  }
  return std::nullopt;
}

std::uint64_t edge_key(meshes::Index a, meshes::Index b) { return (std::uint64_t(a) << 32) | b; }

/// Nodal forces per (cell, node), summed in a fixed order.
using NodalForces = std::map<std::pair<std::size_t, meshes::Index>, std::array<double, 2>>;

void add_force(NodalForces& nodal, std::size_t cell, meshes::Index node, double fx, double fy) {
  auto& f = nodal[{cell, node}];
  f[0] += fx;
  f[1] += fy;
}

/// Uniform pressure normal to a flat, pointing into the disc, on the edge a-b.
void add_flat_edge(NodalForces& nodal, std::size_t cell, const meshes::BoundaryEdge& e, const meshes::Mesh& m, bool top,
                   double pressure) {
  const auto& a = m.nodes[e.a];
  const auto& b = m.nodes[e.b];
  const double lx = b.x - a.x, ly = b.y - a.y, l = std::hypot(lx, ly);
  const double sign = top ? -1.0 : 1.0;  // top pushed down, bottom up
  const double f = 0.5 * pressure * l;
  add_force(nodal, cell, e.a, 0.0, sign * f);
  add_force(nodal, cell, e.b, 0.0, sign * f);
}

/// Radial pressure on the rim arc between the edge's two nodes (measure R dθ, shape functions
/// linear in θ), clipped to the loading arcs |θ ∓ π/2| <= α; 8-point Gauss-Legendre.
void add_arc_edge(NodalForces& nodal, std::size_t cell, const meshes::BoundaryEdge& e, const meshes::Mesh& m,
                  const StaticSetup& st) {
  static constexpr std::array<double, 8> gx{0.0198550717512319, 0.1016667612931866, 0.2372337950418355,
                                            0.4082826787521751, 0.5917173212478249, 0.7627662049581645,
                                            0.8983332387068134, 0.9801449282487681};
  static constexpr std::array<double, 8> gw{0.0506142681451881, 0.1111905172266872, 0.1568533229389436,
                                            0.1813418916891810, 0.1813418916891810, 0.1568533229389436,
                                            0.1111905172266872, 0.0506142681451881};
  const auto& a = m.nodes[e.a];
  const auto& b = m.nodes[e.b];
  const double ta = std::atan2(a.y, a.x);
  double tb = std::atan2(b.y, b.x);
  while (tb - ta > kPi) tb -= 2 * kPi;
  while (tb - ta < -kPi) tb += 2 * kPi;
  const double lo = std::min(ta, tb), hi = std::max(ta, tb);
  for (const double centre : {kPi / 2, -kPi / 2, 3 * kPi / 2, -3 * kPi / 2}) {
    const double c0 = std::max(lo, centre - st.half_angle), c1 = std::min(hi, centre + st.half_angle);
    if (c1 <= c0) continue;
    for (std::size_t q = 0; q < gx.size(); ++q) {
      const double t = c0 + gx[q] * (c1 - c0);
      const double w = gw[q] * (c1 - c0) * st.pressure * st.radius;
      const double s = (t - ta) / (tb - ta);  // shape function of b
      const double fx = -w * std::cos(t), fy = -w * std::sin(t);
      add_force(nodal, cell, e.a, (1.0 - s) * fx, (1.0 - s) * fy);
      add_force(nodal, cell, e.b, s * fx, s * fy);
    }
  }
}

/// Consistent nodal forces of the scene's pressure on the DDA mesh's loaded boundary edges.
std::vector<dda::PointLoad> consistent_loads(const meshes::Mesh& m, const StaticSetup& st) {
  std::unordered_map<std::uint64_t, std::size_t> owner;  // directed edge -> cell
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    const auto n = m.cell_size(c);
    const auto* nodes = m.cell_begin(c);
    for (std::size_t k = 0; k < n; ++k) {
      owner[edge_key(nodes[k], nodes[(k + 1) % n])] = c;
      owner[edge_key(nodes[(k + 1) % n], nodes[k])] = c;
    }
  }
  NodalForces nodal;
  for (const auto& e : m.boundary_edges) {
    const std::string& group = m.boundary_names.at(e.group);
    const auto it = owner.find(edge_key(e.a, e.b));
    if (it == owner.end()) continue;
    if (st.flattened) {
      if (group == "flat_top" || group == "flat_bottom")
        add_flat_edge(nodal, it->second, e, m, group == "flat_top", st.pressure);
    } else if (group == "rim" || group == "load_top" || group == "load_bottom") {
      add_arc_edge(nodal, it->second, e, m, st);
    }
  }
  std::vector<dda::PointLoad> loads;
  for (const auto& [key, f] : nodal) {
    const auto& p = m.nodes[key.second];
    loads.push_back({static_cast<dda::Index>(key.first), p.x, p.y, f[0], f[1]});
  }
  return loads;
}

/// The anchors hold the disc against rigid-body motion only: after each step their targets are
/// moved to where the deformation (the anchored points' motion minus its least-squares rigid
/// part) took them, so in the converged state they carry k·(rigid part), which the balanced
/// loads keep at round-off. Returns the largest rigid displacement of an anchored point (m).
double follow_deformation(std::vector<dda::Anchor>& anchors, const std::vector<std::array<double, 2>>& start) {
  const double n = static_cast<double>(anchors.size());
  double cx = 0, cy = 0, tx = 0, ty = 0;
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    cx += start[i][0] / n;
    cy += start[i][1] / n;
    tx += (anchors[i].x - start[i][0]) / n;
    ty += (anchors[i].y - start[i][1]) / n;
  }
  double num = 0, den = 0;  // small rotation about the anchors' centroid
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    const double rx = start[i][0] - cx, ry = start[i][1] - cy;
    const double ux = anchors[i].x - start[i][0] - tx, uy = anchors[i].y - start[i][1] - ty;
    num += rx * uy - ry * ux;
    den += rx * rx + ry * ry;
  }
  const double theta = num / den;
  double largest = 0.0;
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    const double rx = start[i][0] - cx, ry = start[i][1] - cy;
    const double gx = tx - theta * ry, gy = ty + theta * rx;  // rigid displacement of this point
    anchors[i].x_start = anchors[i].x - gx;
    anchors[i].y_start = anchors[i].y - gy;
    largest = std::max(largest, std::hypot(gx, gy));
  }
  return largest;
}

/// The consistent loads (and their resultants, for the report) and the four anchors.
dda::EngineOptions static_engine_options(const meshes::Mesh& mesh, const StaticSetup& st, double young,
                                         StaticDdaRun& out) {
  dda::EngineOptions eo;
  eo.solver.kind = dda::SolverKind::Direct;
  eo.point_loads = consistent_loads(mesh, st);
  double sx = 0.0, sy = 0.0;
  for (const auto& l : eo.point_loads) {
    sx += l.fx;
    sy += l.fy;
    if (l.y > 0.0) out.applied_top += l.fy;
  }
  out.applied_resultant = std::hypot(sx, sy);
  out.loads = eo.point_loads.size();
  const double r = kAnchorRadiusShare * st.radius;
  for (const auto& [x, y] : {std::pair{r, 0.0}, std::pair{-r, 0.0}, std::pair{0.0, r}, std::pair{0.0, -r}}) {
    const auto c = cell_containing(mesh, x, y);
    if (!c) throw std::runtime_error(fmt::format("verify_static: no DDA block at ({}, {}) for an anchor", x, y));
    eo.anchors.push_back({static_cast<dda::Index>(*c), x, y, x, y, 0.0, 0.0});
  }
  out.anchors = eo.anchors.size();
  eo.anchor_penalty_factor = kAnchorStiffnessOverYoung * young / out.kn;
  eo.allowed_displacement = kStaticAllowedDisplacementOverPE * st.load / young;
  return eo;
}

/// Undeformed centroids and areas of the blocks, and their mean size.
void record_blocks(const dda::BlockSystem& b, StaticDdaRun& out) {
  out.blocks.resize(b.block_count());
  double area = 0.0;
  for (std::size_t i = 0; i < b.block_count(); ++i) {
    out.blocks[i].x = b.geometry[i].cx;
    out.blocks[i].y = b.geometry[i].cy;
    out.blocks[i].area = b.geometry[i].area;
    area += b.geometry[i].area;
  }
  out.mean_block_size = std::sqrt(area / static_cast<double>(b.block_count()));
}

/// Steps until the last step moved no vertex by more than kStaticTolerance of the largest total
/// displacement (at least two steps), or max_steps.
void step_to_rest(dda::Engine& engine, double pressure, int max_steps, bool quiet, StaticDdaRun& out) {
  const auto& b = engine.blocks();
  const std::vector<double> x0 = b.vx, y0 = b.vy;
  std::vector<std::array<double, 2>> anchor_start;
  for (const auto& a : b.anchors) anchor_start.push_back({a.x, a.y});
  std::vector<dda::Vec3> previous = b.stress;
  int taken = 0;  // steps
  dda::DriveHooks hooks;
  hooks.before_step = [&] { return taken < max_steps ? dda::Next::Continue : dda::Next::Stop; };
  hooks.after_step = [&](const dda::StepReport& report) {
    ++taken;
    out.anchor_rigid = follow_deformation(engine.blocks().anchors, anchor_start);
    out.steps = report.step;
    out.dt_cuts += report.cuts;
    double total = 0.0;
    for (std::size_t v = 0; v < b.vx.size(); ++v) total = std::max(total, std::hypot(b.vx[v] - x0[v], b.vy[v] - y0[v]));
    out.max_total_displacement = total;
    out.last_step_ratio = report.max_displacement / std::max(total, 1e-300);
    out.step_ratios.push_back(out.last_step_ratio);
    double change = 0.0;
    for (std::size_t i = 0; i < b.block_count(); ++i)
      change = std::max(change, (b.stress[i] - previous[i]).cwiseAbs().maxCoeff());
    out.last_stress_change = change / pressure;
    previous = b.stress;
    if (!quiet)
      fmt::print(
          "verify: DDA step {}: largest step displacement / total {:.2e}, largest stress change / pressure {:.2e}\n",
          report.step, out.last_step_ratio, out.last_stress_change);
    return taken >= 2 && out.last_step_ratio < kStaticTolerance ? dda::Next::Stop : dda::Next::Continue;
  };
  dda::drive(engine, std::numeric_limits<double>::infinity(), hooks);  // no end time: until at rest
}

}  // namespace

StaticDdaRun run_static_dda(const scene::Scene& scene, const StaticSetup& st, const VerifyOptions& o) {
  const common::ThreadScope threads(o.threads);
  StaticDdaRun out;
  const auto start = Clock::now();
  const DdaTwin twin = static_twin(scene, o.stiffness_ratio);
  out.kn = twin.kn;
  out.ks_over_kn = twin.ks_over_kn;
  out.dt = twin.scene.analysis.dt_max;
  const auto mesh = meshes::generate_dda_mesh(st.dda_geometry, scene.mesh);
  out.mesh_wall = seconds_since(start);
  const double young = twin.scene.materials.at(twin.scene.bodies.at(0).material).young;
  const dda::EngineOptions eo = static_engine_options(mesh, st, young, out);
  out.solver = "direct (sparse LDLT)";
  out.engine = std::make_unique<dda::Engine>(twin.scene, mesh, eo);
  dda::Engine& engine = *out.engine;
  const auto& b = engine.blocks();
  if (b.block_count() != mesh.cell_count()) throw std::logic_error("verify_static: blocks are not the mesh cells");
  record_blocks(b, out);
  step_to_rest(engine, st.pressure, o.max_steps > 0 ? o.max_steps : kStaticDefaultMaxSteps, o.quiet, out);
  out.anchor_force = eo.anchor_penalty_factor * out.kn * out.anchor_rigid;
  for (std::size_t i = 0; i < out.blocks.size(); ++i)
    out.blocks[i].stress = {b.stress[i][0], b.stress[i][1], b.stress[i][2]};
  out.wall = seconds_since(start);
  return out;
}

}  // namespace ddafrac::coupling
