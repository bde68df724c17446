#include "ddafrac/coupling/verify_dynamic.hpp"

#include <fmt/core.h>
#include <nlohmann/json.hpp>
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>
#include <variant>

#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/reference/analytic.hpp"
#include "ddafrac/coupling/dda_twin.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/dda/run.hpp"
#include "ddafrac/fem/dynamic_problem.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/scene/scene.hpp"
#include "thread_scope.hpp"

namespace ddafrac::coupling {

using reference::arrival_time;
using reference::compare_histories;
using reference::Elastic;
using reference::History;
using reference::impact_plane_wave_stress;
using reference::p_wave_speed;
using reference::peak_of;
using reference::PlaneModel;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

constexpr double kElementsPerDiameter = 25.0;   // FEM element size D/25, as `ddafrac fem`
constexpr double kFemDtCap = 2.5e-8;            // s: c_p dt = 0.06 mm << h = 4 mm
constexpr double kFemSampleInterval = 1e-7;     // s between FEM gauge samples (a point search each)
constexpr double kJointCompliance = 1.35;       // α of 1/E_eff = 1/E + α/kn (test dda_fracture)
constexpr double kMPa = 1e-6;
constexpr double kPi = 3.14159265358979323846;
// A reference arrival earlier than this share of (distance from the patch) / c_p is a numerical
// precursor of the FEM (P2 with consistent mass sends its short waves ahead of the front), not
// the wave: such a gauge is not checked. 10% leaves room for the front smeared over an element.
constexpr double kPhysicalArrivalShare = 0.9;

const meshes::ImpactDisc& impact_geometry(const scene::Scene& s) {
  const auto* g = std::get_if<meshes::ImpactDisc>(&s.geometry);
  if (!g) throw std::runtime_error(s.source.string() + ": the dynamic comparison needs an impact_disc geometry");
  return *g;
}

double impact_speed(const scene::Scene& s) {
  const auto& v = disc_body(s).initial_velocity;
  return std::hypot(v[0], v[1]);
}

double end_time_of(const scene::Scene& s, const ImpactSettings& settings) {
  return settings.end_time > 0.0 ? settings.end_time : s.analysis.end_time;
}

double dda_dt_of(const scene::Scene& s, const ImpactSettings& settings) {
  return settings.dda_dt > 0.0 ? settings.dda_dt : s.analysis.dt_max;
}

/// The scene's DDA mesh without the plate: only the cells of the disc body.
meshes::Mesh disc_only(const meshes::Mesh& mesh, const std::string& disc) {
  meshes::Mesh out;
  out.nodes = mesh.nodes;
  out.body_names = mesh.body_names;
  out.boundary_edges = mesh.boundary_edges;
  out.boundary_names = mesh.boundary_names;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.body_names[mesh.cell_body[c]] != disc) continue;
    out.cell_nodes.insert(out.cell_nodes.end(), mesh.cell_begin(c), mesh.cell_begin(c) + mesh.cell_size(c));
    out.cell_offsets.push_back(static_cast<meshes::Index>(out.cell_nodes.size()));
    out.cell_body.push_back(mesh.cell_body[c]);
  }
  return out;
}

/// Fixed points at every block vertex on the impact patch (the FEM holds the same nodes).
std::vector<dda::Anchor> patch_anchors(const meshes::Mesh& mesh) {
  const auto group = std::find(mesh.boundary_names.begin(), mesh.boundary_names.end(), "impact_patch");
  if (group == mesh.boundary_names.end()) throw std::runtime_error("the DDA mesh has no impact_patch boundary group");
  const auto g = static_cast<meshes::Index>(group - mesh.boundary_names.begin());
  std::set<meshes::Index> nodes;
  for (const auto& e : mesh.boundary_edges)
    if (e.group == g) nodes.insert({e.a, e.b});
  std::vector<dda::Anchor> anchors;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    for (const meshes::Index* n = mesh.cell_begin(c); n != mesh.cell_begin(c) + mesh.cell_size(c); ++n)
      if (nodes.count(*n)) {
        dda::Anchor a;
        a.block = static_cast<dda::Index>(c);
        a.x = a.x_start = mesh.nodes[*n].x;
        a.y = a.y_start = mesh.nodes[*n].y;
        anchors.push_back(a);
      }
  return anchors;
}

void push_sample(GaugeHistories& h, std::size_t g, double t, double syy, double s1) {
  h.syy[g].t.push_back(t);
  h.syy[g].v.push_back(syy);
  h.s1[g].t.push_back(t);
  h.s1[g].v.push_back(s1);
}

void name_gauges(GaugeHistories& h, const scene::Scene& s) {
  const fem::Material m = disc_material(s);
  h.plane_wave_stress = std::abs(impact_plane_wave_stress(m.elastic, m.plane, impact_speed(s)));
  // A gauge closer to the joint slot than one DDA block (the mean edge of an equilateral
  // triangle of the disc's area / target blocks) reports a block average over a region where σyy
  // changes by its full size: its arrival is reported, not checked.
  const auto& geometry = impact_geometry(s);
  const double block_size = std::sqrt(4.0 * kPi * geometry.diameter * geometry.diameter / 4.0 /
                                      (std::sqrt(3.0) * std::max(1, s.mesh.target_blocks)));
  const double half_length = 0.5 * geometry.connectivity * geometry.diameter;
  const double cx = std::cos(geometry.joint_angle), cy = std::sin(geometry.joint_angle);
  // Earliest physical arrival: the straight-line distance from the impact patch over c_p.
  const double cp = p_wave_speed(m.elastic, m.plane);
  const double radius = 0.5 * geometry.diameter;
  for (const auto& g : s.gauges) {
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = -50; k <= 50; ++k) {
      const double angle = -0.5 * kPi + geometry.patch_half_angle * k / 50.0;
      nearest = std::min(nearest, std::hypot(g.position[0] - radius * std::cos(angle), g.position[1] - radius * std::sin(angle)));
    }
    h.earliest_arrival.push_back(nearest / cp);
    h.names.push_back(g.name);
    const double along = std::clamp(g.position[0] * cx + g.position[1] * cy, -half_length, half_length);
    const double distance =
        std::hypot(g.position[0] - along * cx, g.position[1] - along * cy) - 0.5 * geometry.joint_width;
    h.near_slot.push_back(distance < block_size);
  }
  h.syy.resize(s.gauges.size());
  h.s1.resize(s.gauges.size());
}

std::string format_mpa(double pa) { return fmt::format("{:.2f}", pa * kMPa); }
std::string format_us(double s) { return fmt::format("{:.2f}", s * 1e6); }
std::string format_percent(double r) { return fmt::format("{:+.1f}%", 100.0 * r); }

}  // namespace

GaugeHistories run_impact_dda(const scene::Scene& scene, const ImpactSettings& settings) {
  impact_geometry(scene);
  const scene::Body& disc = disc_body(scene);
  const double young = disc_material(scene).elastic.young;
  DdaTwin bonded = bonded_dda_twin(scene, settings.stiffness_ratio);
  scene::Scene& twin = bonded.scene;
  twin.analysis.mode = scene::Mode::Dynamic;
  twin.analysis.dt_max = dda_dt_of(scene, settings);
  twin.analysis.end_time = end_time_of(scene, settings);

  GaugeHistories out;
  name_gauges(out, scene);
  const auto mesh_start = Clock::now();
  const meshes::Mesh mesh = disc_only(meshes::generate_dda_mesh(scene.geometry, scene.mesh), disc.name);
  out.mesh_wall = seconds_since(mesh_start);

  const ThreadScope threads(settings.threads);
  const auto start = Clock::now();
  dda::EngineOptions options;
  options.anchors = patch_anchors(mesh);
  options.anchor_penalty_factor = settings.anchor_ratio * young / twin.analysis.penalty;
  dda::Engine engine(twin, mesh, options);
  out.blocks = engine.blocks().block_count();
  out.joints = engine.blocks().joints.size();
  out.dt = twin.analysis.dt_max;
  out.kn = bonded.kn;
  const auto& gauge_blocks = engine.gauge_blocks();
  const auto sample = [&] {
    for (std::size_t g = 0; g < gauge_blocks.size(); ++g) {
      const auto& stress = engine.blocks().stress[static_cast<std::size_t>(gauge_blocks[g])];
      double s1 = 0.0, s3 = 0.0;
      dda::principal_stresses(stress, s1, s3);
      push_sample(out, g, engine.time(), stress[1], s1);
    }
  };
  sample();
  const double end = twin.analysis.end_time;
  while (engine.time() < end * (1.0 - 1e-12)) {
    if (settings.max_steps > 0 && out.steps >= settings.max_steps) break;
    const dda::StepReport r = engine.step(end - engine.time());
    ++out.steps;
    sample();
    if (!settings.quiet && out.steps % 200 == 0)
      fmt::print("  DDA step {} t = {:.2f} µs, CG {}\n", out.steps, engine.time() * 1e6, r.cg_iterations);
  }
  const auto& st = engine.statistics();
  out.cg_total = st.cg_total;
  out.cg_max = st.cg_max;
  out.open_close_total = st.open_close_total;
  out.dt_cuts = st.cuts_displacement + st.cuts_open_close + st.cuts_solver;
  out.wall = seconds_since(start);
  return out;
}

GaugeHistories run_impact_fem(const scene::Scene& scene, const ImpactSettings& settings) {
  const auto& geometry = impact_geometry(scene);
  GaugeHistories out;
  name_gauges(out, scene);
  const auto mesh_start = Clock::now();
  fem::DynamicProblem p;
  const double size = settings.fem_element_size > 0.0 ? settings.fem_element_size : geometry.diameter / kElementsPerDiameter;
  p.mesh = meshes::generate_fem_mesh(scene.geometry, size, meshes::FemCells::Triangles);
  out.mesh_wall = seconds_since(mesh_start);
  const auto start = Clock::now();
  p.material = disc_material(scene);
  p.discretisation = {settings.fem_degree, settings.fem_refine};
  p.newmark = {settings.fem_beta, settings.fem_gamma};
  p.v0 = impact_speed(scene);
  p.dt = settings.fem_dt > 0.0 ? settings.fem_dt : std::min(dda_dt_of(scene, settings), kFemDtCap);
  p.end_time = end_time_of(scene, settings);
  p.output_interval = std::max(p.dt, kFemSampleInterval);
  for (const auto& g : scene.gauges) p.gauges.push_back({g.name, g.position[0], g.position[1]});
  const fem::DynamicResult r = fem::run_dynamic(p);
  for (const auto& g : r.gauges) push_sample(out, g.gauge, g.t, g.sample.stress.yy, g.sample.s1);
  out.dofs = r.stats.dofs;
  out.fem_solver = r.stats.solver;
  out.steps = r.steps;
  out.dt = p.dt;
  out.wall = seconds_since(start);
  return out;
}

std::vector<GaugeError> compare_gauges(const GaugeHistories& model, const GaugeHistories& reference,
                                       const ImpactSettings& settings) {
  if (model.names != reference.names) throw std::invalid_argument("compare_gauges: the two runs have different gauges");
  std::vector<GaugeError> out;
  for (std::size_t g = 0; g < model.names.size(); ++g) {
    GaugeError e;
    e.gauge = model.names[g];
    e.syy = compare_histories(model.syy[g], reference.syy[g], 1.0);
    // Arrival: both histories against the same absolute level, a share of the plane-wave stress.
    const double level = settings.arrival_fraction * reference.plane_wave_stress;
    const auto arrival = [level](const History& h) {
      const double peak = std::abs(peak_of(h).value);
      return peak > level ? arrival_time(h, level / peak) : h.t.back();
    };
    e.syy.reference_arrival = arrival(reference.syy[g]);
    e.syy.approximation_arrival = arrival(model.syy[g]);
    const double peak = std::abs(e.syy.reference_peak.value);
    e.peak_error = (std::abs(e.syy.approximation_peak.value) - peak) / peak;
    e.arrival_error = (e.syy.approximation_arrival - e.syy.reference_arrival) / e.syy.reference_arrival;
    e.arrival_checked = e.syy.reference_arrival >= settings.min_arrival_time && !reference.near_slot[g] &&
                        e.syy.reference_arrival >= kPhysicalArrivalShare * reference.earliest_arrival[g];
    e.s1_rms_over_peak = compare_histories(model.s1[g], reference.s1[g], settings.arrival_fraction).rms_over_peak;
    out.push_back(e);
  }
  return out;
}

ImpactErrorSummary summarise(std::vector<GaugeError> gauges) {
  ImpactErrorSummary s;
  s.gauges = std::move(gauges);
  for (const auto& g : s.gauges) {
    s.max_rms = std::max(s.max_rms, g.syy.rms_over_peak);
    s.mean_rms += g.syy.rms_over_peak;
    s.mean_abs_peak += std::abs(g.peak_error);
    s.max_abs_peak = std::max(s.max_abs_peak, std::abs(g.peak_error));
    if (g.arrival_checked) s.max_abs_arrival = std::max(s.max_abs_arrival, std::abs(g.arrival_error));
  }
  if (!s.gauges.empty()) {
    s.mean_rms /= static_cast<double>(s.gauges.size());
    s.mean_abs_peak /= static_cast<double>(s.gauges.size());
  }
  return s;
}

double effective_modulus_ratio(double kn_over_e) { return 1.0 / (1.0 + kJointCompliance / kn_over_e); }

void write_gauge_histories(const std::filesystem::path& file,
                           const std::vector<std::pair<std::string, const GaugeHistories*>>& models) {
  std::ostringstream text;
  text << "t,model,gauge,syy,s1\n";
  for (const auto& [label, h] : models)
    for (std::size_t g = 0; g < h->names.size(); ++g)
      for (std::size_t i = 0; i < h->syy[g].t.size(); ++i)
        text << fmt::format("{:.9g},{},{},{:.9g},{:.9g}\n", h->syy[g].t[i], label, h->names[g], h->syy[g].v[i],
                            h->s1[g].v[i]);
  common::write_whole_text(file, text.str());
}

VerificationReport verify_dynamic(const scene::Scene& scene, const VerifyOptions& options) {
  const auto& geometry = impact_geometry(scene);
  const fem::Material material = disc_material(scene);
  const Elastic& m = material.elastic;
  ImpactSettings settings;
  settings.stiffness_ratio = options.stiffness_ratio;
  settings.threads = options.threads;
  settings.max_steps = options.max_steps;
  settings.fem_degree = options.fem_degree;
  settings.fem_refine = options.fem_refine;
  settings.quiet = options.quiet;
  const auto say = [&](const std::string& what) {
    if (!options.quiet) fmt::print("{}\n", what);
  };

  say("verify: DDA twin (bonded, unbreakable virtual joints; impact patch held; no gravity)");
  const GaugeHistories dda = run_impact_dda(scene, settings);
  say(fmt::format("verify: DDA {} blocks, {} steps, {:.1f} s; FEM reference (Newmark 1/4, 1/2)", dda.blocks,
                  dda.steps, dda.wall));
  const GaugeHistories fem = run_impact_fem(scene, settings);
  // The FEM with the DDA's Newmark (1/2, 1) at the DDA's dt: its distance from the reference is
  // the part of the DDA's error that comes from time integration alone.
  ImpactSettings dda_scheme = settings;
  dda_scheme.fem_beta = 0.5;
  dda_scheme.fem_gamma = 1.0;
  dda_scheme.fem_dt = dda.dt;
  say(fmt::format("verify: FEM {} dofs, {:.1f} s; FEM with the DDA's Newmark (1/2, 1) at dt = {:.3g} s", fem.dofs,
                  fem.wall, dda.dt));
  const GaugeHistories fem_dda_scheme = run_impact_fem(scene, dda_scheme);

  const auto errors = compare_gauges(dda, fem, settings);
  const auto time_errors = compare_gauges(fem_dda_scheme, fem, settings);
  const ImpactErrorSummary summary = summarise(errors);

  std::filesystem::create_directories(options.out_dir);
  write_gauge_histories(options.out_dir / "impact_gauges.csv",
                        {{"FEM", &fem}, {"DDA", &dda}, {"FEM-half-one", &fem_dda_scheme}});
  std::ostringstream csv;
  csv << "gauge,x,y,fem_peak_syy,fem_peak_time,dda_peak_syy,dda_peak_time,peak_error,fem_arrival,dda_arrival,"
         "arrival_error,arrival_checked,rms_over_peak_syy,rms_over_peak_s1,fem_half_one_rms_over_peak_syy\n";
  for (std::size_t g = 0; g < errors.size(); ++g) {
    const auto& e = errors[g];
    csv << fmt::format("{},{:.6g},{:.6g},{:.9g},{:.9g},{:.9g},{:.9g},{:.6g},{:.9g},{:.9g},{:.6g},{},{:.6g},{:.6g},{:.6g}\n",
                       e.gauge, scene.gauges[g].position[0], scene.gauges[g].position[1], e.syy.reference_peak.value,
                       e.syy.reference_peak.time, e.syy.approximation_peak.value, e.syy.approximation_peak.time,
                       e.peak_error, e.syy.reference_arrival, e.syy.approximation_arrival, e.arrival_error,
                       e.arrival_checked ? 1 : 0, e.syy.rms_over_peak, e.s1_rms_over_peak,
                       time_errors[g].syy.rms_over_peak);
  }
  common::write_whole_text(options.out_dir / "impact_gauge_errors.csv", csv.str());

  VerificationReport report;
  report.title = "Contact-free impact: DDA twin vs FEM gauge histories";
  report.dda_wall = dda.wall;
  report.fem_wall = fem.wall;
  const auto& tolerances = scene.verification;
  for (const auto& e : errors) {
    if (tolerances && tolerances->arrival_time && e.arrival_checked)
      report.checks.push_back({fmt::format("P-wave arrival at gauge {}, DDA vs FEM", e.gauge), "arrival_time",
                               std::abs(e.arrival_error), *tolerances->arrival_time});
    if (tolerances && tolerances->gauge_rms)
      report.checks.push_back({fmt::format("σyy history at gauge {}: RMS error / |FEM peak|", e.gauge), "gauge_rms",
                               e.syy.rms_over_peak, *tolerances->gauge_rms});
  }

  const Elastic& elastic = m;
  const PlaneModel plane = material.plane;
  const double cp = p_wave_speed(elastic, plane);
  const double ratio = dda.kn / m.young;
  const double e_eff = effective_modulus_ratio(ratio);
  std::ostringstream md;
  md << fmt::format("## {}\n\n", report.title);
  md << fmt::format(
      "Scene `{}`: impact disc D = {:.0f} mm with its joint slot (θ = {:.0f}°, γ = {:.2f}, width {:.1f} mm, open and "
      "traction-free in both models), v0 = {:.2f} m/s, impact patch of half-angle {:.1f}° held from t = 0, no "
      "gravity, {:.0f} µs. E = {:.4g} GPa, ν = {}, ρ = {:.0f} kg/m³, c_p = {:.1f} m/s ({}), plane-wave stress "
      "−ρ c_p v0 = {:.2f} MPa.\n\n",
      scene.name, geometry.diameter * 1e3, geometry.joint_angle * 180.0 / kPi, geometry.connectivity,
      geometry.joint_width * 1e3, impact_speed(scene), geometry.patch_half_angle * 180.0 / kPi,
      end_time_of(scene, settings) * 1e6, m.young * 1e-9, m.poisson, m.density, cp,
      plane == PlaneModel::Stress ? "plane stress" : "plane strain",
      impact_plane_wave_stress(elastic, plane, impact_speed(scene)) * kMPa);
  md << "| model | settings | run time (s) |\n|---|---|---|\n";
  md << fmt::format(
      "| DDA twin | {} blocks, {} bonded unbreakable virtual joints, kn = {:.4g} N/m (kn/E = {:.4g}), patch vertices "
      "held by fixed points of {:.0f} E, dt = {:.3g} s, Newmark (½, 1), {} steps, {} CG iterations (max {} per "
      "solve), {} dt cuts, {} thread(s) | {:.2f} (+ {:.2f} meshing) |\n",
      dda.blocks, dda.joints, dda.kn, ratio, settings.anchor_ratio, dda.dt, dda.steps, dda.cg_total, dda.cg_max,
      dda.dt_cuts, settings.threads, dda.wall, dda.mesh_wall);
  md << fmt::format(
      "| FEM reference | P{} triangles, {} refinement(s), element size D/{:.0f}, {} dofs, Newmark (¼, ½), dt = {:.3g} "
      "s, {} steps, {} | {:.2f} |\n",
      settings.fem_degree, settings.fem_refine, kElementsPerDiameter, fem.dofs, fem.dt, fem.steps, fem.fem_solver,
      fem.wall);
  md << fmt::format("| FEM, DDA's scheme | as the reference but Newmark (½, 1) at dt = {:.3g} s | {:.2f} |\n\n",
                    fem_dda_scheme.dt, fem_dda_scheme.wall);
  md << fmt::format(
      "Joint compliance: with 1/E_eff = 1/E + {:.2f}/kn the DDA's effective modulus is {:.4f} E, so its P wave is "
      "expected {:.1f}% slower (arrivals {:+.1f}%).\n\n",
      kJointCompliance, e_eff, 100.0 * (1.0 - std::sqrt(e_eff)), 100.0 * (1.0 / std::sqrt(e_eff) - 1.0));
  md << fmt::format(
      "σyy per gauge (arrival: first time |σyy| reaches {:.0f}% of ρ c_p v0; arrival checked where the "
      "FEM's arrival is ≥ {:.0f} µs and ≥ 0.9 × (distance from the patch)/c_p, i.e. not a precursor of the FEM, and the "
      "gauge is more than one DDA block from the slot). The last column is the FEM with the DDA's Newmark (½, 1) at the DDA's dt "
      "against the reference: the time-integration share of the error.\n\n",
      100.0 * settings.arrival_fraction, settings.min_arrival_time * 1e6);
  md << "| gauge | x, y (mm) | FEM peak (MPa) at µs | DDA peak (MPa) at µs | peak error | FEM arrival (µs) | DDA "
        "arrival (µs) | arrival error | RMS/peak σyy | RMS/peak σ1 | FEM (½,1) RMS/peak |\n"
        "|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (std::size_t g = 0; g < errors.size(); ++g) {
    const auto& e = errors[g];
    md << fmt::format("| {} | {:.1f}, {:.1f} | {} at {} | {} at {} | {} | {} | {} | {}{} | {:.3f} | {:.3f} | {:.3f} |\n",
                      e.gauge, scene.gauges[g].position[0] * 1e3, scene.gauges[g].position[1] * 1e3,
                      format_mpa(e.syy.reference_peak.value), format_us(e.syy.reference_peak.time),
                      format_mpa(e.syy.approximation_peak.value), format_us(e.syy.approximation_peak.time),
                      format_percent(e.peak_error), format_us(e.syy.reference_arrival),
                      format_us(e.syy.approximation_arrival), format_percent(e.arrival_error),
                      e.arrival_checked ? "" : " (not checked)", e.syy.rms_over_peak, e.s1_rms_over_peak,
                      time_errors[g].syy.rms_over_peak);
  }
  md << fmt::format(
      "\nOver all gauges: RMS/peak σyy mean {:.3f}, max {:.3f}; |peak error| mean {:.1f}%, max {:.1f}%; largest "
      "checked |arrival error| {:.1f}%.\n\n",
      summary.mean_rms, summary.max_rms, 100.0 * summary.mean_abs_peak, 100.0 * summary.max_abs_peak,
      100.0 * summary.max_abs_arrival);
  md << "Files: `impact_gauges.csv` (t, model, gauge, σyy, σ1 of the three runs), `impact_gauge_errors.csv`, "
        "`comparison.json`.\n\n";
  md << "![σyy at the gauges, DDA twin vs FEM](impact_gauges_syy.png)\n\n";
  md << "![σ1 at the gauges, DDA twin vs FEM](impact_gauges_s1.png)\n\n";
  report.markdown = md.str();

  // Machine-readable numbers (ddafrac study convergence reads blocks, steps and fem_dofs).
  nlohmann::json gauges = nlohmann::json::array();
  for (std::size_t g = 0; g < errors.size(); ++g) {
    const auto& e = errors[g];
    gauges.push_back({{"gauge", e.gauge}, {"rms_over_peak_syy", e.syy.rms_over_peak},
                      {"rms_over_peak_s1", e.s1_rms_over_peak}, {"peak_error", e.peak_error},
                      {"fem_peak_syy", e.syy.reference_peak.value}, {"dda_peak_syy", e.syy.approximation_peak.value},
                      {"fem_arrival", e.syy.reference_arrival}, {"dda_arrival", e.syy.approximation_arrival},
                      {"arrival_error", e.arrival_error}, {"arrival_checked", e.arrival_checked},
                      {"fem_half_one_rms_over_peak_syy", time_errors[g].syy.rms_over_peak}});
  }
  const nlohmann::json j{{"kind", "impact"},
                         {"blocks", dda.blocks},
                         {"steps", dda.steps},
                         {"dda_wall", dda.wall},
                         {"fem_wall", fem.wall},
                         {"fem_dofs", fem.dofs},
                         {"kn_over_E", ratio},
                         {"dt", dda.dt},
                         {"cg_total", dda.cg_total},
                         {"dt_cuts", dda.dt_cuts},
                         {"mean_rms_over_peak", summary.mean_rms},
                         {"max_rms_over_peak", summary.max_rms},
                         {"max_abs_arrival_error", summary.max_abs_arrival},
                         {"mean_abs_peak_error", summary.mean_abs_peak},
                         {"gauges", gauges}};
  common::write_whole_text(options.out_dir / "comparison.json", j.dump(2) + "\n");
  return report;
}

}  // namespace ddafrac::coupling
