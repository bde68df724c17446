// The static Brazilian disc three ways: DDA twin (bonded, unbreakable virtual joints, stiff
// joint springs, static mode), FEM reference and, for the plain disc, the Hondros series.
//
// Both models carry the same load: the FEM as a boundary pressure, the DDA as the consistent
// nodal forces of the same pressure on its rim vertices (PointLoad). The DDA's rigid-body modes
// are removed by four anchors at (±R/2, 0), (0, ±R/2) whose targets follow the deformation, so
// that they resist rigid-body motion only: the loads are self-equilibrated and symmetric, so
// in the converged state the anchors carry round-off (their largest force is reported).

#include "ddafrac/coupling/verify_static.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <variant>

#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/reference/analytic.hpp"
#include "ddafrac/reference/compare.hpp"
#include "ddafrac/coupling/dda_twin.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/fem/static_problem.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

using reference::Disc;
using reference::HondrosLoad;
using reference::Stress2;

namespace {

constexpr double pi = 3.14159265358979323846;
constexpr double fem_elements_per_diameter = 25.0;  // as `ddafrac fem`
constexpr int profile_points = 201;
// Anchors k = 0.05 E (N/m): stiff enough against the rotation that the two dead loads drive
// (their couple P·D·θ; four anchors at R/2 resist with k·R² per radian).
constexpr double anchor_stiffness_over_young = 0.05;
constexpr double static_tolerance = 1e-7;  // last step's largest displacement / largest total displacement
constexpr int default_max_steps = 40;

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Tensor {
  double xx = 0.0, yy = 0.0, xy = 0.0;
};
Tensor from(const Stress2& s) { return {s.xx, s.yy, s.xy}; }

/// What the static comparison needs to know about the geometry.
struct Setup {
  double diameter = 0.0;
  double radius = 0.0;
  bool flattened = false;
  double half_angle = 0.0;  // Hondros arcs (plain/slit disc) or half the flat angle (flattened)
  double load = 0.0;        // N/m, nominal diametral load P
  double pressure = 0.0;    // Pa
  std::optional<meshes::Slit> slit;
  bool analytic = false;    // the Hondros series applies (plain disc without slit)
  meshes::Geometry dda_geometry, fem_geometry;
};

Setup make_setup(const scene::Scene& s) {
  Setup out;
  out.diameter = disc_diameter(s.geometry);
  out.radius = 0.5 * out.diameter;
  out.load = *s.verification->load;
  out.dda_geometry = out.fem_geometry = s.geometry;
  if (auto* flat = std::get_if<meshes::FlattenedDisc>(&out.dda_geometry)) {
    flat->with_platens = false;  // loaded on the flats directly, like the FEM
    std::get<meshes::FlattenedDisc>(out.fem_geometry).with_platens = false;
    out.flattened = true;
    out.half_angle = 0.5 * flat->flat_angle;
    out.pressure = out.load / (out.diameter * std::sin(out.half_angle));  // load / flat width
    out.slit = flat->slit;
  } else if (const auto* plain = std::get_if<meshes::PlainDisc>(&s.geometry)) {
    out.half_angle = plain->load_half_angle > 0.0 ? plain->load_half_angle : default_arc_half_angle;
    out.pressure = out.load / (out.half_angle * out.diameter);  // P = 2αR p
    out.analytic = true;
  } else if (const auto* slit = std::get_if<meshes::SlitDisc>(&s.geometry)) {
    out.half_angle = default_arc_half_angle;
    out.pressure = out.load / (out.half_angle * out.diameter);
    out.slit = slit->slit;
  } else {
    throw std::invalid_argument("verify_static: the scene is not a static Brazilian disc (plain, flattened or slit disc)");
  }
  return out;
}

/// The static DDA twin: the bonded twin of the disc alone, in static mode.
scene::Scene static_twin(const scene::Scene& scene, const VerifyOptions& o, double& kn, double& ks_over_kn) {
  DdaTwin twin = bonded_dda_twin(scene, o.stiffness_ratio);
  kn = twin.kn;
  ks_over_kn = twin.ks_over_kn;
  scene::Scene& s = twin.scene;
  s.bodies.erase(std::remove_if(s.bodies.begin(), s.bodies.end(),
                                [](const scene::Body& b) { return b.role != scene::Role::Disc; }),
                 s.bodies.end());
  s.analysis.mode = scene::Mode::Static;
  s.analysis.dt_max = 1e-2;  // static mode: the inertia term 2M/dt² is then ~1e-6 of the stiffness
  s.gauges.clear();
  return std::move(twin.scene);
}

double cross(double ax, double ay, double bx, double by) { return ax * by - ay * bx; }

bool inside_cell(const meshes::Mesh& m, std::size_t c, double x, double y) {
  const auto n = m.cell_size(c);
  const auto* nodes = m.cell_begin(c);
  int sign = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const auto& p = m.nodes[nodes[k]];
    const auto& q = m.nodes[nodes[(k + 1) % n]];
    const double c2 = cross(q.x - p.x, q.y - p.y, x - p.x, y - p.y);
    const int s = c2 > 0.0 ? 1 : (c2 < 0.0 ? -1 : 0);
    if (s != 0) {
      if (sign != 0 && s != sign) return false;
      sign = s;
    }
  }
  return true;
}

std::optional<std::size_t> cell_containing(const meshes::Mesh& m, double x, double y) {
  for (std::size_t c = 0; c < m.cell_count(); ++c)
    if (inside_cell(m, c, x, y)) return c;
  return std::nullopt;
}

std::uint64_t edge_key(meshes::Index a, meshes::Index b) { return (std::uint64_t(a) << 32) | b; }

/// Consistent nodal forces of the scene's pressure on the DDA mesh's loaded boundary edges.
std::vector<dda::PointLoad> consistent_loads(const meshes::Mesh& m, const Setup& st) {
  std::unordered_map<std::uint64_t, std::size_t> owner;  // directed edge -> cell
  for (std::size_t c = 0; c < m.cell_count(); ++c) {
    const auto n = m.cell_size(c);
    const auto* nodes = m.cell_begin(c);
    for (std::size_t k = 0; k < n; ++k) {
      owner[edge_key(nodes[k], nodes[(k + 1) % n])] = c;
      owner[edge_key(nodes[(k + 1) % n], nodes[k])] = c;
    }
  }
  std::map<std::pair<std::size_t, meshes::Index>, std::array<double, 2>> nodal;  // (cell, node) -> force
  auto add = [&](std::size_t cell, meshes::Index node, double fx, double fy) {
    auto& f = nodal[{cell, node}];
    f[0] += fx;
    f[1] += fy;
  };
  // 8-point Gauss-Legendre on [0, 1].
  static constexpr std::array<double, 8> gx{0.0198550717512319, 0.1016667612931866, 0.2372337950418355,
                                            0.4082826787521751, 0.5917173212478249, 0.7627662049581645,
                                            0.8983332387068134, 0.9801449282487681};
  static constexpr std::array<double, 8> gw{0.0506142681451881, 0.1111905172266872, 0.1568533229389436,
                                            0.1813418916891810, 0.1813418916891810, 0.1568533229389436,
                                            0.1111905172266872, 0.0506142681451881};
  for (const auto& e : m.boundary_edges) {
    const std::string& group = m.boundary_names.at(e.group);
    const auto it = owner.find(edge_key(e.a, e.b));
    if (it == owner.end()) continue;
    const std::size_t cell = it->second;
    const auto& a = m.nodes[e.a];
    const auto& b = m.nodes[e.b];
    if (st.flattened) {
      if (group != "flat_top" && group != "flat_bottom") continue;
      // Uniform pressure normal to the flat, pointing into the disc.
      const double lx = b.x - a.x, ly = b.y - a.y, l = std::hypot(lx, ly);
      const double sign = group == "flat_top" ? -1.0 : 1.0;  // top pushed down, bottom up
      const double f = 0.5 * st.pressure * l;
      add(cell, e.a, 0.0, sign * f);
      add(cell, e.b, 0.0, sign * f);
      continue;
    }
    if (group != "rim" && group != "load_top" && group != "load_bottom") continue;
    // Radial pressure on the rim arc between the two nodes (measure R dθ, shape functions
    // linear in θ), clipped to the loading arcs |θ ∓ π/2| <= α.
    const double ta = std::atan2(a.y, a.x);
    double tb = std::atan2(b.y, b.x);
    while (tb - ta > pi) tb -= 2 * pi;
    while (tb - ta < -pi) tb += 2 * pi;
    const double lo = std::min(ta, tb), hi = std::max(ta, tb);
    for (const double centre : {pi / 2, -pi / 2, 3 * pi / 2, -3 * pi / 2}) {
      const double c0 = std::max(lo, centre - st.half_angle), c1 = std::min(hi, centre + st.half_angle);
      if (c1 <= c0) continue;
      for (std::size_t q = 0; q < gx.size(); ++q) {
        const double t = c0 + gx[q] * (c1 - c0);
        const double w = gw[q] * (c1 - c0) * st.pressure * st.radius;
        const double s = (t - ta) / (tb - ta);  // shape function of b
        const double fx = -w * std::cos(t), fy = -w * std::sin(t);
        add(cell, e.a, (1.0 - s) * fx, (1.0 - s) * fy);
        add(cell, e.b, s * fx, s * fy);
      }
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

struct BlockResult {
  double x = 0.0, y = 0.0, area = 0.0;  // undeformed centroid, m; m²
  Tensor dda, fem, ana;
  bool has_fem = false;
};

struct DdaRun {
  std::vector<BlockResult> blocks;
  std::size_t block_count = 0;
  long steps = 0;
  double wall = 0.0, mesh_wall = 0.0;
  double last_step_ratio = 0.0;     // last step's largest displacement / largest total displacement
  double last_stress_change = 0.0;  // max |Δσ| over the last step / reference stress scale
  std::vector<double> step_ratios;  // per step: largest step displacement / largest total displacement
  double max_total_displacement = 0.0;
  double anchor_rigid = 0.0;        // largest rigid-body displacement the anchors resisted, m
  double anchor_force = 0.0;        // largest anchor spring force, N/m
  double applied_resultant = 0.0;   // |Σ f| of the point loads, N/m
  double applied_top = 0.0;         // vertical resultant on the upper half, N/m
  double kn = 0.0;
  double ks_over_kn = 0.0;         // of the bonded joints
  double mean_block_size = 0.0;
  long dt_cuts = 0;
  std::string solver;
  std::size_t loads = 0;            // point loads
  std::unique_ptr<dda::Engine> engine;
};

DdaRun run_dda(const scene::Scene& scene, const Setup& st, const VerifyOptions& o) {
  DdaRun out;
  const auto start = Clock::now();
  scene::Scene twin = static_twin(scene, o, out.kn, out.ks_over_kn);
  const auto mesh = meshes::generate_dda_mesh(st.dda_geometry, scene.mesh);
  out.mesh_wall = seconds_since(start);
  const double young = twin.materials.at(twin.bodies.at(0).material).young;
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
  for (const auto& [x, y] : {std::pair{0.5 * st.radius, 0.0}, std::pair{-0.5 * st.radius, 0.0}, std::pair{0.0, 0.5 * st.radius},
                             std::pair{0.0, -0.5 * st.radius}}) {
    const auto c = cell_containing(mesh, x, y);
    if (!c) throw std::runtime_error(fmt::format("verify_static: no DDA block at ({}, {}) for an anchor", x, y));
    eo.anchors.push_back({static_cast<dda::Index>(*c), x, y, x, y, 0.0, 0.0});
  }
  eo.anchor_penalty_factor = anchor_stiffness_over_young * young / out.kn;
  eo.allowed_displacement = 10.0 * st.load / young;
  eo.search_distance_factor = 0.25;
  out.solver = "direct (sparse LDLT)";
  out.engine = std::make_unique<dda::Engine>(twin, mesh, eo);
  dda::Engine& engine = *out.engine;
  const auto& b = engine.blocks();
  if (b.block_count() != mesh.cell_count()) throw std::logic_error("verify_static: blocks are not the mesh cells");
  const std::vector<double> x0 = b.vx, y0 = b.vy;
  std::vector<std::array<double, 2>> anchor_start;
  for (const auto& a : b.anchors) anchor_start.push_back({a.x, a.y});
  out.block_count = b.block_count();
  out.blocks.resize(out.block_count);
  double area = 0.0;
  for (std::size_t i = 0; i < out.block_count; ++i) {
    out.blocks[i].x = b.geometry[i].cx;
    out.blocks[i].y = b.geometry[i].cy;
    out.blocks[i].area = b.geometry[i].area;
    area += b.geometry[i].area;
  }
  out.mean_block_size = std::sqrt(area / static_cast<double>(out.block_count));
  const double scale = st.pressure;
  const int max_steps = o.max_steps > 0 ? o.max_steps : default_max_steps;
  std::vector<dda::Vec3> previous = b.stress;
  for (int k = 0; k < max_steps; ++k) {
    const auto report = engine.step();
    out.anchor_rigid = follow_deformation(engine.blocks().anchors, anchor_start);
    out.steps = report.step;
    out.dt_cuts += report.cuts;
    double total = 0.0;
    for (std::size_t v = 0; v < b.vx.size(); ++v) total = std::max(total, std::hypot(b.vx[v] - x0[v], b.vy[v] - y0[v]));
    out.max_total_displacement = total;
    out.last_step_ratio = report.max_displacement / std::max(total, 1e-300);
    out.step_ratios.push_back(out.last_step_ratio);
    double change = 0.0;
    for (std::size_t i = 0; i < out.block_count; ++i) change = std::max(change, (b.stress[i] - previous[i]).cwiseAbs().maxCoeff());
    out.last_stress_change = change / scale;
    previous = b.stress;
    if (!o.quiet)
      fmt::print("verify: DDA step {}: largest step displacement / total {:.2e}, largest stress change / pressure {:.2e}\n",
                 report.step, out.last_step_ratio, out.last_stress_change);
    if (k >= 1 && out.last_step_ratio < static_tolerance) break;
  }
  out.anchor_force = eo.anchor_penalty_factor * out.kn * out.anchor_rigid;
  for (std::size_t i = 0; i < out.block_count; ++i) out.blocks[i].dda = {b.stress[i][0], b.stress[i][1], b.stress[i][2]};
  out.wall = seconds_since(start);
  return out;
}

struct FemRun {
  std::optional<fem::StaticSolution> solution;
  double wall = 0.0;
  std::size_t dofs = 0, cells = 0;
  int iterations = 0;
  double element_size = 0.0;
};

FemRun run_fem(const scene::Scene& scene, const Setup& st, const VerifyOptions& o) {
  FemRun out;
  const auto start = Clock::now();
  out.element_size = st.diameter / fem_elements_per_diameter;
  fem::StaticProblem problem;
  problem.mesh = meshes::generate_fem_mesh(st.fem_geometry, out.element_size, meshes::FemCells::Triangles);
  problem.material = disc_material(scene);
  problem.discretisation = {o.fem_degree, o.fem_refine};
  if (st.flattened)
    problem.load = fem::FlatLoad{st.pressure, 0.0};
  else
    problem.load = fem::ArcPressure{st.pressure, st.half_angle};
  out.solution.emplace(fem::solve_static(problem));
  out.wall = seconds_since(start);
  out.dofs = out.solution->stats().dofs;
  out.cells = out.solution->stats().cells;
  out.iterations = out.solution->stats().iterations;
  return out;
}

/// FEM stress at a point; a point just outside the FEM's polygonal rim is pulled inwards.
std::optional<Tensor> fem_at(const fem::StaticSolution& s, double x, double y) {
  for (int k = 0; k < 6; ++k) {
    const double f = 1.0 - 1e-3 * k;
    try {
      return from(s.stress_at(f * x, f * y).stress);
    } catch (const fem::FemError&) {
    }
  }
  return std::nullopt;
}

/// Area-weighted relative L2 error of the three components together and of each one alone.
struct FieldError {
  double all = 0.0, xx = 0.0, yy = 0.0, xy = 0.0;
};

/// Blocks with centroid radius above `max_radius` are left out.
FieldError field_error(const std::vector<BlockResult>& blocks, Tensor BlockResult::*approx, Tensor BlockResult::*ref,
                       double max_radius = std::numeric_limits<double>::infinity()) {
  std::vector<double> a, r, axx, rxx, ayy, ryy, axy, rxy;
  for (const auto& b : blocks) {
    if (!b.has_fem || std::hypot(b.x, b.y) > max_radius) continue;
    const double w = std::sqrt(b.area);
    const Tensor& p = b.*approx;
    const Tensor& q = b.*ref;
    // τxy counts twice in the Frobenius norm of the tensor.
    for (const auto& [va, vr] : {std::pair{p.xx, q.xx}, std::pair{p.yy, q.yy}, std::pair{std::sqrt(2.0) * p.xy, std::sqrt(2.0) * q.xy}}) {
      a.push_back(w * va);
      r.push_back(w * vr);
    }
    axx.push_back(w * p.xx);
    rxx.push_back(w * q.xx);
    ayy.push_back(w * p.yy);
    ryy.push_back(w * q.yy);
    axy.push_back(w * p.xy);
    rxy.push_back(w * q.xy);
  }
  return {reference::relative_l2_error(a, r), reference::relative_l2_error(axx, rxx), reference::relative_l2_error(ayy, ryy), reference::relative_l2_error(axy, rxy)};
}

/// Area-weighted mean over the blocks whose centroid lies within `radius` of the centre.
Tensor centre_mean(const std::vector<BlockResult>& blocks, Tensor BlockResult::*which, double radius) {
  Tensor s;
  double w = 0.0;
  for (const auto& b : blocks) {
    if (std::hypot(b.x, b.y) > radius || !b.has_fem) continue;
    const Tensor& t = b.*which;
    s.xx += b.area * t.xx;
    s.yy += b.area * t.yy;
    s.xy += b.area * t.xy;
    w += b.area;
  }
  if (w > 0.0) {
    s.xx /= w;
    s.yy /= w;
    s.xy /= w;
  }
  return s;
}

double rel(double a, double r) { return std::abs(a - r) / std::abs(r); }

std::string mpa(double v) { return fmt::format("{:.4f}", v / 1e6); }

}  // namespace

VerificationReport verify_static(const scene::Scene& scene, const VerifyOptions& options) {
  if (!scene.verification || !scene.verification->load)
    throw std::invalid_argument(fmt::format("{}: verification.load is missing (the diametral load of the comparison, N/m)",
                                            scene.source.string()));
  const Setup st = make_setup(scene);
  const auto& tol = *scene.verification;
  const int threads_before = omp_get_max_threads();
  omp_set_num_threads(std::max(1, options.threads));
  if (!options.quiet) fmt::print("verify: DDA twin of {} ({} blocks target), static, P = {:.4g} N/m\n", scene.name, scene.mesh.target_blocks, st.load);
  DdaRun dda;
  try {
    dda = run_dda(scene, st, options);
  } catch (...) {
    omp_set_num_threads(threads_before);
    throw;
  }
  omp_set_num_threads(threads_before);
  if (!options.quiet) fmt::print("verify: DDA {} blocks, {} steps, {:.2f} s; FEM p = {}, {} refinement(s)\n", dda.block_count, dda.steps, dda.wall, options.fem_degree, options.fem_refine);
  const FemRun fem = run_fem(scene, st, options);
  if (!options.quiet) fmt::print("verify: FEM {} dofs, {:.2f} s\n", fem.dofs, fem.wall);

  // References at the block centroids.
  const Disc disc{st.diameter, 1.0};
  const HondrosLoad hondros{st.load, st.half_angle};
  std::size_t missing = 0;
  for (auto& b : dda.blocks) {
    if (const auto f = fem_at(*fem.solution, b.x, b.y)) {
      b.fem = *f;
      b.has_fem = true;
    } else {
      ++missing;
    }
    if (st.analytic) b.ana = from(reference::hondros_series(disc, hondros, b.x, b.y));
  }

  // Centre: area-weighted means over the blocks within R/10 of the centre, every source
  // sampled at the same centroids (a slit disc has no material at the centre: skipped).
  const double centre_radius = 0.1 * st.radius;
  const Tensor c_dda = centre_mean(dda.blocks, &BlockResult::dda, centre_radius);
  const Tensor c_fem = centre_mean(dda.blocks, &BlockResult::fem, centre_radius);
  const Tensor c_ana = centre_mean(dda.blocks, &BlockResult::ana, centre_radius);
  const bool has_centre = !st.slit;
  const Stress2 point_ana = reference::hondros_centre(disc, hondros);

  const FieldError e_fem = field_error(dda.blocks, &BlockResult::dda, &BlockResult::fem);
  const double inner_radius = 0.8 * st.radius;  // away from the loaded arcs and flats
  const FieldError e_inner = field_error(dda.blocks, &BlockResult::dda, &BlockResult::fem, inner_radius);
  FieldError e_ana, e_fem_ana;
  if (st.analytic) {
    e_ana = field_error(dda.blocks, &BlockResult::dda, &BlockResult::ana);
    e_fem_ana = field_error(dda.blocks, &BlockResult::fem, &BlockResult::ana);
  }

  // The worst 1% of blocks against the FEM, with where and why.
  double ref_rms = 0.0, wsum = 0.0;
  for (const auto& b : dda.blocks)
    if (b.has_fem) {
      ref_rms += b.area * (b.fem.xx * b.fem.xx + b.fem.yy * b.fem.yy + 2 * b.fem.xy * b.fem.xy);
      wsum += b.area;
    }
  ref_rms = std::sqrt(ref_rms / wsum);
  struct Worst {
    std::size_t block;
    double error;
  };
  std::vector<Worst> worst;
  for (std::size_t i = 0; i < dda.blocks.size(); ++i) {
    const auto& b = dda.blocks[i];
    if (!b.has_fem) continue;
    const double dxx = b.dda.xx - b.fem.xx, dyy = b.dda.yy - b.fem.yy, dxy = b.dda.xy - b.fem.xy;
    worst.push_back({i, std::sqrt(dxx * dxx + dyy * dyy + 2 * dxy * dxy) / ref_rms});
  }
  std::sort(worst.begin(), worst.end(), [](const Worst& a, const Worst& b) { return a.error > b.error || (a.error == b.error && a.block < b.block); });
  if (!worst.empty()) worst.resize(std::max<std::size_t>(1, worst.size() / 100));
  const double h = dda.mean_block_size;
  auto reason = [&](const BlockResult& b) -> std::string {
    const double r = std::hypot(b.x, b.y);
    const double theta = std::atan2(b.y, b.x);
    if (st.slit) {
      const double c = std::cos(st.slit->inclination), s = std::sin(st.slit->inclination);
      for (const double sign : {1.0, -1.0})
        if (std::hypot(b.x - sign * 0.5 * st.slit->length * c, b.y - sign * 0.5 * st.slit->length * s) < 3.0 * h)
          return "near a slit tip";
    }
    if (st.flattened && std::abs(b.y) > st.radius * std::cos(st.half_angle) - 3.0 * h && std::abs(b.x) < st.radius * std::sin(st.half_angle) + 3.0 * h)
      return b.y > 0 ? "near the top flat" : "near the bottom flat (supports differ)";
    const double from_axis = std::min(std::abs(theta - pi / 2), std::abs(theta + pi / 2));
    if (!st.flattened && r > st.radius - 3.0 * h && from_axis < st.half_angle + 3.0 * h / st.radius) return "near a loaded arc";
    if (r > st.radius - 1.5 * h) return "at the free rim";
    return "interior";
  };
  std::map<std::string, int> reasons;
  for (const auto& w : worst) ++reasons[reason(dda.blocks[w.block])];

  // Profiles along the loaded (x = 0) and the horizontal (y = 0) diameter.
  const auto& blocks = dda.engine->blocks();
  std::ostringstream prof;
  prof << "profile,s,x,y,dda_sxx,dda_syy,dda_txy,fem_sxx,fem_syy,fem_txy,ana_sxx,ana_syy,ana_txy\n";
  const double rr = st.radius * (1.0 - 1e-6);
  const double ry = st.flattened ? rr * std::cos(st.half_angle) : rr;
  for (const auto& [name, x0, y0, x1, y1] : {std::tuple{"loaded", 0.0, -ry, 0.0, ry}, std::tuple{"horizontal", -rr, 0.0, rr, 0.0}}) {
    for (int k = 0; k < profile_points; ++k) {
      const double t = static_cast<double>(k) / (profile_points - 1);
      const double x = x0 + t * (x1 - x0), y = y0 + t * (y1 - y0);
      const auto blk = dda::find_block(blocks, x, y);
      const auto f = fem_at(*fem.solution, x, y);
      if (blk < 0 || !f) continue;  // inside a slit or just outside a polygonal rim
      const auto& s = blocks.stress[static_cast<std::size_t>(blk)];
      Tensor a{std::nan(""), std::nan(""), std::nan("")};
      if (st.analytic) a = from(reference::hondros_series(disc, hondros, x, y));
      prof << fmt::format("{},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", name,
                          x0 == x1 ? y : x, x, y, s[0], s[1], s[2], f->xx, f->yy, f->xy, a.xx, a.yy, a.xy);
    }
  }
  std::ostringstream cents;
  cents << "block,x,y,area,dda_sxx,dda_syy,dda_txy,fem_sxx,fem_syy,fem_txy,ana_sxx,ana_syy,ana_txy\n";
  for (std::size_t i = 0; i < dda.blocks.size(); ++i) {
    const auto& b = dda.blocks[i];
    cents << fmt::format("{},{:.9g},{:.9g},{:.6g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g},{:.9g}\n", i, b.x, b.y, b.area,
                         b.dda.xx, b.dda.yy, b.dda.xy, b.fem.xx, b.fem.yy, b.fem.xy, b.ana.xx, b.ana.yy, b.ana.xy);
  }
  std::filesystem::create_directories(options.out_dir);
  common::write_whole_text(options.out_dir / "profiles.csv", prof.str());
  common::write_whole_text(options.out_dir / "blocks.csv", cents.str());

  // Checks against the scene's tolerances.
  VerificationReport rep;
  rep.dda_wall = dda.wall;
  rep.fem_wall = fem.wall;
  rep.title = st.analytic ? "Static Brazilian disc: DDA vs FEM vs Hondros" : "Static Brazilian disc: DDA vs FEM";
  if (tol.centre_stress && has_centre) {
    rep.checks.push_back({"centre sxx, DDA vs FEM", "centre_stress", rel(c_dda.xx, c_fem.xx), *tol.centre_stress});
    rep.checks.push_back({"centre syy, DDA vs FEM", "centre_stress", rel(c_dda.yy, c_fem.yy), *tol.centre_stress});
    if (st.analytic) {
      rep.checks.push_back({"centre sxx, DDA vs Hondros", "centre_stress", rel(c_dda.xx, c_ana.xx), *tol.centre_stress});
      rep.checks.push_back({"centre syy, DDA vs Hondros", "centre_stress", rel(c_dda.yy, c_ana.yy), *tol.centre_stress});
    }
  }
  if (tol.field_l2) {
    rep.checks.push_back({"field L2 (sxx, syy, txy), DDA vs FEM", "field_l2", e_fem.all, *tol.field_l2});
    if (st.analytic) rep.checks.push_back({"field L2 (sxx, syy, txy), DDA vs Hondros", "field_l2", e_ana.all, *tol.field_l2});
  }

  // verification.md section.
  std::ostringstream md;
  const auto& mat = disc_material(scene);
  md << "## " << rep.title << "\n\n";
  md << fmt::format("Disc D = {} mm, E = {:.4g} GPa, ν = {}, plane {}; ", st.diameter * 1e3, mat.elastic.young / 1e9, mat.elastic.poisson,
                    mat.plane == fem::PlaneModel::Stress ? "stress" : "strain");
  if (st.flattened)
    md << fmt::format("flattened disc (flats of {:.1f}°), uniform pressure {:.4g} MPa on both flats (load P = {:.4g} N/m).\n\n",
                      2 * st.half_angle * 180 / pi, st.pressure / 1e6, st.load);
  else
    md << fmt::format("Hondros arcs 2α = {:.1f}°, radial pressure p = {:.4g} MPa (nominal load P = 2αRp = {:.4g} N/m).{}\n\n",
                      2 * st.half_angle * 180 / pi, st.pressure / 1e6, st.load, st.slit ? " Central slit." : "");
  md << "### Models\n\n| | settings | run time (s) |\n|---|---|---|\n";
  md << fmt::format("| DDA | {} blocks (mean size {:.2f} mm), virtual joints bonded and unbreakable (σt = c = ∞), kn = {:.3g} N/m "
                    "= {:.0f}·E, ks = {:g}·kn; static mode (velocities reset every step), dt = {:.0e} s (inertia ≈ 0), {} solver; "
                    "{} consistent nodal loads (resultant {:.2e} N/m; vertical load on the upper half {:.6g} N/m); 4 anchors "
                    "(0.05·E N/m) that follow the deformation and resist only rigid-body motion | {:.2f} (mesh {:.2f}) |\n",
                    dda.block_count, h * 1e3, dda.kn, dda.kn / mat.elastic.young, dda.ks_over_kn, 1e-2, dda.solver, dda.loads, dda.applied_resultant,
                    dda.applied_top, dda.wall, dda.mesh_wall);
  md << fmt::format("| FEM | P{} triangles, element size {:.1f} mm, {} refinement(s): {} cells, {} dofs, CG+AMG {} iterations; load as a "
                    "boundary pressure{} | {:.2f} |\n",
                    options.fem_degree, fem.element_size * 1e3, options.fem_refine, fem.cells, fem.dofs, fem.iterations,
                    st.flattened ? " on the top flat, bottom flat on rollers (u_y = 0)" : " on the arcs (rigid modes pinned, no pin force)", fem.wall);
  if (st.flattened)
    md << "\nThe supports differ under the bottom flat: the FEM holds it on rollers (the reaction concentrates at the flat's "
          "edges), the DDA carries the same uniform pressure on both flats (no supports: a DDA anchor would hold both "
          "components). The centre and the field away from the bottom flat are unaffected; the blocks next to it are not.\n";
  if (st.analytic) md << "| analytic | Hondros (1959) Fourier series at every block centroid | – |\n";
  md << "\n";
  md << fmt::format(
      "How the DDA reached a static state: static mode (velocities reset every step, so the kinetic energy is zero by "
      "construction and the measure of equilibrium is what the last step still changed), {} steps (dt cuts: {}); the last step moved no vertex by more than {:.2e} "
      "of the largest total displacement ({:.3e} m) and changed no block stress by more than {:.2e} of the pressure. Largest "
      "anchor force {:.3g} N/m ({:.1e} of the load).\n\n",
      dda.steps, dda.dt_cuts, dda.last_step_ratio, dda.max_total_displacement, dda.last_stress_change, dda.anchor_force,
      dda.anchor_force / st.load);
  md << "Largest step displacement / largest total displacement, step by step:";
  for (const double r : dda.step_ratios) md << fmt::format(" {:.1e}", r);
  md << ".\n\n";
  if (dda.last_step_ratio >= static_tolerance) {
    md << fmt::format("**Warning: the DDA did not reach a static state within {} steps** (last step / total displacement {:.2e}, "
                      "wanted below {:.0e}); the comparison below is of an unconverged state.\n\n",
                      dda.steps, dda.last_step_ratio, static_tolerance);
    if (!options.quiet) fmt::print("verify: warning: the DDA did not reach a static state within {} steps\n", dda.steps);
  }
  if (has_centre) {
    md << fmt::format("### Centre stresses (MPa)\n\nArea-weighted mean over the blocks with centroid within R/10 = {:.1f} mm of the "
                      "centre, every source sampled at the same centroids.\n\n",
                      centre_radius * 1e3);
    md << "| | σxx | σyy | τxy |\n|---|---|---|---|\n";
    md << fmt::format("| DDA | {} | {} | {} |\n| FEM | {} | {} | {} |\n", mpa(c_dda.xx), mpa(c_dda.yy), mpa(c_dda.xy), mpa(c_fem.xx), mpa(c_fem.yy), mpa(c_fem.xy));
    if (st.analytic) {
      md << fmt::format("| Hondros | {} | {} | {} |\n", mpa(c_ana.xx), mpa(c_ana.yy), mpa(c_ana.xy));
      md << fmt::format("| Hondros at the centre point | {} | {} | 0 |\n", mpa(point_ana.xx), mpa(point_ana.yy));
    } else if (st.flattened) {
      const auto arc = reference::flattened_disc_centre_arc_mapped(disc, st.load, 2 * st.half_angle);
      md << fmt::format("| arc-mapped approximation at the centre (not checked) | {} | {} | 0 |\n", mpa(arc.xx), mpa(arc.yy));
    }
    md << fmt::format("\nDDA vs FEM: σxx {:.2f}%, σyy {:.2f}%", 100 * rel(c_dda.xx, c_fem.xx), 100 * rel(c_dda.yy, c_fem.yy));
    if (st.analytic) md << fmt::format("; DDA vs Hondros: σxx {:.2f}%, σyy {:.2f}%; FEM vs Hondros: σxx {:.2f}%, σyy {:.2f}%", 100 * rel(c_dda.xx, c_ana.xx), 100 * rel(c_dda.yy, c_ana.yy), 100 * rel(c_fem.xx, c_ana.xx), 100 * rel(c_fem.yy, c_ana.yy));
    md << ".\n\n";
  }
  md << "### Field errors at the block centroids\n\nRelative L2, area-weighted, over every disc block";
  if (missing) md << fmt::format(" ({} centroids outside the FEM mesh left out)", missing);
  md << ".\n\n| | (σxx, σyy, τxy) | σxx | σyy | τxy |\n|---|---|---|---|---|\n";
  md << fmt::format("| DDA vs FEM | {:.4f} | {:.4f} | {:.4f} | {:.4f} |\n", e_fem.all, e_fem.xx, e_fem.yy, e_fem.xy);
  md << fmt::format("| DDA vs FEM, inner disc r < 0.8 R (away from the loads) | {:.4f} | {:.4f} | {:.4f} | {:.4f} |\n", e_inner.all,
                    e_inner.xx, e_inner.yy, e_inner.xy);
  if (st.analytic) {
    md << fmt::format("| DDA vs Hondros | {:.4f} | {:.4f} | {:.4f} | {:.4f} |\n", e_ana.all, e_ana.xx, e_ana.yy, e_ana.xy);
    md << fmt::format("| FEM vs Hondros (quality of the reference) | {:.5f} | {:.5f} | {:.5f} | {:.5f} |\n", e_fem_ana.all, e_fem_ana.xx, e_fem_ana.yy, e_fem_ana.xy);
  }
  md << fmt::format("\n### The worst 1% of blocks (DDA vs FEM)\n\nPointwise error |σ_DDA − σ_FEM| (tensor norm) over the RMS FEM stress "
                    "({:.3g} MPa). Where they are: ",
                    ref_rms / 1e6);
  bool first = true;
  for (const auto& [why, n] : reasons) {
    md << (first ? "" : ", ") << fmt::format("{} {}", n, why);
    first = false;
  }
  md << fmt::format(" (\"near\" = within 3 mean block sizes, {:.1f} mm).\n\n| block | r/R | angle (°) | error | σxx DDA / FEM (MPa) | σyy DDA / FEM (MPa) | why |\n|---|---|---|---|---|---|---|\n", 3 * h * 1e3);
  for (std::size_t k = 0; k < std::min<std::size_t>(worst.size(), 15); ++k) {
    const auto& b = dda.blocks[worst[k].block];
    md << fmt::format("| {} | {:.3f} | {:.1f} | {:.3f} | {} / {} | {} / {} | {} |\n", worst[k].block, std::hypot(b.x, b.y) / st.radius,
                      std::atan2(b.y, b.x) * 180 / pi, worst[k].error, mpa(b.dda.xx), mpa(b.fem.xx), mpa(b.dda.yy), mpa(b.fem.yy), reason(b));
  }
  if (worst.size() > 15) md << fmt::format("\n({} more in blocks.csv.)\n", worst.size() - 15);
  md << "\n### Profiles\n\n`profiles.csv` (DDA block stress, FEM and analytic at the same points along both diameters), "
        "`blocks.csv` (every block centroid, all sources).\n\n"
        "![sxx and syy along the loaded diameter](profile_loaded.png)\n\n"
        "![sxx and syy along the horizontal diameter](profile_horizontal.png)\n\n";
  rep.markdown = md.str();

  nlohmann::json j{{"kind", "static"},
                   {"blocks", dda.block_count},
                   {"steps", dda.steps},
                   {"dda_wall", dda.wall},
                   {"fem_wall", fem.wall},
                   {"fem_dofs", fem.dofs},
                   {"kn_over_E", dda.kn / mat.elastic.young},
                   {"load", st.load},
                   {"last_step_ratio", dda.last_step_ratio},
                   {"anchor_force", dda.anchor_force},
                   {"field_l2_fem", {{"all", e_fem.all}, {"sxx", e_fem.xx}, {"syy", e_fem.yy}, {"txy", e_fem.xy}}},
                   {"field_l2_fem_inner", e_inner.all}};
  if (has_centre) {
    j["centre"] = {{"dda", {c_dda.xx, c_dda.yy, c_dda.xy}}, {"fem", {c_fem.xx, c_fem.yy, c_fem.xy}}};
    j["centre_error_fem"] = {rel(c_dda.xx, c_fem.xx), rel(c_dda.yy, c_fem.yy)};
  }
  if (st.analytic) {
    j["field_l2_analytic"] = {{"all", e_ana.all}, {"sxx", e_ana.xx}, {"syy", e_ana.yy}, {"txy", e_ana.xy}};
    j["field_l2_fem_vs_analytic"] = e_fem_ana.all;
    if (has_centre) {
      j["centre"]["analytic"] = {c_ana.xx, c_ana.yy, c_ana.xy};
      j["centre_error_analytic"] = {rel(c_dda.xx, c_ana.xx), rel(c_dda.yy, c_ana.yy)};
    }
  }
  j["worst_reasons"] = reasons;
  common::write_whole_text(options.out_dir / "comparison.json", j.dump(2) + "\n");
  return rep;
}

}  // namespace ddafrac::coupling
