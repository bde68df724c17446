#include "ddafrac/coupling/stability.hpp"

#include <fmt/core.h>
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "ddafrac/dda/drive.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/dda/run.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/scene/parse.hpp"

namespace ddafrac::coupling {

namespace {

double triangle_area(const meshes::Point& a, const meshes::Point& b, const meshes::Point& c) {
  return 0.5 * ((b.x - a.x) * (c.y - a.y) - (c.x - a.x) * (b.y - a.y));
}

/// Mean over the triangular blocks of each block's smallest altitude (2·area / longest edge), m.
double mean_smallest_altitude(const dda::BlockSystem& b) {
  double sum = 0.0;
  long count = 0;
  for (std::size_t i = 0; i < b.block_count(); ++i) {
    if (b.end(i) - b.begin(i) != 3) continue;
    double longest = 0.0;
    for (dda::Index v = b.begin(i); v < b.end(i); ++v) {
      const dda::Index w = v + 1 < b.end(i) ? v + 1 : b.begin(i);
      longest = std::max(longest, std::hypot(b.vx[w] - b.vx[v], b.vy[w] - b.vy[v]));
    }
    sum += 2.0 * b.geometry[i].area / longest;
    ++count;
  }
  return count > 0 ? sum / static_cast<double>(count) : 0.0;
}

bool all_vertices_finite(const dda::BlockSystem& b) {
  for (std::size_t v = 0; v < b.vertex_count(); ++v)
    if (!std::isfinite(b.vx[v]) || !std::isfinite(b.vy[v])) return false;
  return true;
}

bool contains_all(const std::string& text, const std::vector<std::string>& parts) {
  return std::all_of(parts.begin(), parts.end(),
                     [&](const std::string& p) { return text.find(p) != std::string::npos; });
}

std::string csv_field(const std::string& s) {
  std::string out = "\"";
  for (char ch : s) out += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return out + "\"";
}

std::string md_field(const std::string& s) {
  std::string out;
  for (char ch : s) out += ch == '|' ? std::string("\\|") : std::string(1, ch);
  return out;
}

}  // namespace

const char* to_string(Verdict v) {
  switch (v) {
    case Verdict::Stable: return "stable";
    case Verdict::PenetrationHigh: return "stable, penetration above allowance";
    case Verdict::FailedCleanly: return "failed cleanly";
    case Verdict::Unstable: return "unstable";
    case Verdict::DidNotFinish: return "did not finish";
    case Verdict::Error: return "error";
  }
  return "?";
}

meshes::Mesh make_sliver_slab_mesh(const SliverSlab& s) {
  meshes::Mesh m;
  m.body_names = {"disc", "plate"};
  const int nx = std::max(1, s.columns), ny = std::max(1, s.rows);
  const double x0 = -0.5 * s.width;
  auto node = [nx](int i, int j) { return static_cast<meshes::Index>(j * (nx + 1) + i); };
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i) m.nodes.push_back({x0 + s.width * i / nx, s.height * j / ny});
  auto cell = [&](std::initializer_list<meshes::Index> nodes, meshes::Index body) {
    m.cell_nodes.insert(m.cell_nodes.end(), nodes);
    m.cell_offsets.push_back(static_cast<meshes::Index>(m.cell_nodes.size()));
    m.cell_body.push_back(body);
  };
  // Each cell cut along alternating diagonals (no preferred direction across the slab), nodes
  // counter-clockwise.
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const meshes::Index a = node(i, j), b = node(i + 1, j), c = node(i + 1, j + 1), d = node(i, j + 1);
      if ((i + j) % 2 == 0) {
        cell({a, b, c}, 0);
        cell({a, c, d}, 0);
      } else {
        cell({a, b, d}, 0);
        cell({b, c, d}, 0);
      }
    }
  if (s.plate_height > 0.0) {
    const auto p = static_cast<meshes::Index>(m.nodes.size());
    const double w = 0.5 * s.plate_width;
    m.nodes.push_back({-w, -s.plate_height});
    m.nodes.push_back({w, -s.plate_height});
    m.nodes.push_back({w, 0.0});
    m.nodes.push_back({-w, 0.0});
    cell({p, p + 1, p + 2, p + 3}, 1);
  }
  return m;
}

double max_aspect_ratio(const meshes::Mesh& mesh, const std::string& body) {
  const auto it = std::find(mesh.body_names.begin(), mesh.body_names.end(), body);
  if (it == mesh.body_names.end()) return 0.0;
  const auto b = static_cast<meshes::Index>(it - mesh.body_names.begin());
  double worst = 0.0;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.cell_body[c] != b || mesh.cell_size(c) != 3) continue;
    const meshes::Index* n = mesh.cell_begin(c);
    const meshes::Point &p = mesh.nodes[n[0]], &q = mesh.nodes[n[1]], &r = mesh.nodes[n[2]];
    const double l2 =
        std::max({std::pow(q.x - p.x, 2) + std::pow(q.y - p.y, 2), std::pow(r.x - q.x, 2) + std::pow(r.y - q.y, 2),
                  std::pow(p.x - r.x, 2) + std::pow(p.y - r.y, 2)});
    worst = std::max(worst, l2 / (2.0 * std::abs(triangle_area(p, q, r))));
  }
  return worst;
}

std::vector<StabilityCase> stability_cases() {
  const std::string impact = "small/impact_small.toml";        // case 4 geometry, kn = 0.35 GPa, 3.5 m/s
  const std::string flattened = "small/flattened_small.toml";  // kn = 10 GPa, platen 0.25 m/s
  // 800 blocks for the impact disc (its slot's graded ends alone take several hundred), 400 for
  // the flattened disc.
  const std::string impact_blocks = "mesh.blocks=800";
  const std::string blocks = "mesh.blocks=400";
  const double young = 10.53e9;  // rock (scenes/common_rock.toml)
  const std::string kn_1e4 = fmt::format("analysis.penalty={:.6g}", 1e4 * young);
  std::vector<StabilityCase> cases;
  auto add = [&](StabilityCase c) {
    if (c.max_steps == 0) c.max_steps = 40000;
    cases.push_back(std::move(c));
  };
  add({"kn-1e2E-dynamic",
       "kn/E = 1e2 (kn = 1.05e12 N/m), impact 3.5 m/s",
       impact,
       {impact_blocks, fmt::format("analysis.penalty={:.6g}", 1e2 * young)},
       std::nullopt,
       50e-6,
       0,
       120.0,
       Expectation::Stable,
       {}});
  // Block-Jacobi PCG needs hundreds of iterations per solve at kn/E >= 1e3: the stiff dynamic
  // cases use the sparse direct solver (same system, same answer to round-off).
  const std::string direct = "analysis.solver=\"direct\"";
  add({"kn-1e3E-dynamic",
       "kn/E = 1e3 (kn = 1.05e13 N/m), impact 3.5 m/s",
       impact,
       {impact_blocks, direct, fmt::format("analysis.penalty={:.6g}", 1e3 * young)},
       std::nullopt,
       100e-6,
       0,
       900.0,
       Expectation::Stable,
       {}});
  add({"kn-1e4E-dynamic",
       "kn/E = 1e4 (kn = 1.05e14 N/m), impact 3.5 m/s",
       impact,
       {impact_blocks, direct, kn_1e4},
       std::nullopt,
       50e-6,
       0,
       900.0,
       Expectation::Stable,
       {}});
  add({"kn-1e4E-static",
       "kn/E = 1e4, static mode, platen 0.25 m/s",
       flattened,
       {blocks, kn_1e4, "analysis.mode=\"static\""},
       std::nullopt,
       200e-6,
       0,
       120.0,
       Expectation::Stable,
       {}});
  add({"dt-1e-5-static",
       "dt_max = 1e-5 s, static mode, platen 0.25 m/s to 0.5 mm (past the peak)",
       flattened,
       {blocks, "analysis.dt_max=1e-5", "analysis.mode=\"static\""},
       std::nullopt,
       2e-3,
       0,
       120.0,
       Expectation::Stable,
       {}});
  add({"dt-1e-5-dynamic",
       "dt_max = 1e-5 s, impact 3.5 m/s",
       impact,
       {impact_blocks, "analysis.dt_max=1e-5"},
       std::nullopt,
       300e-6,
       0,
       120.0,
       Expectation::Stable,
       {}});
  add({"dt-1e-9-dynamic",
       "dt_max = 1e-9 s, impact 3.5 m/s",
       impact,
       {impact_blocks, "analysis.dt_max=1e-9"},
       std::nullopt,
       2e-6,
       0,
       120.0,
       Expectation::Stable,
       {}});
  add({"v0-50",
       "impact at v0 = 50 m/s",
       impact,
       {impact_blocks, "bodies.disc.velocity=[0.0, -50.0]"},
       std::nullopt,
       100e-6,
       0,
       120.0,
       Expectation::Stable,
       {}});
  add({"sliver",
       "slab of sliver triangles (16.7 mm x 0.67 mm cells), impact 3.5 m/s",
       impact,
       {},
       SliverSlab{},
       100e-6,
       0,
       120.0,
       Expectation::Stable,
       {}});
  const std::vector<std::string> stiff_platens{blocks,
                                               "materials.stiff.density=2050.0",
                                               fmt::format("materials.stiff.young={:.6g}", 100.0 * young),
                                               "materials.stiff.poisson=0.12",
                                               "bodies.top_platen.material=\"stiff\"",
                                               "bodies.bottom_platen.material=\"stiff\"",
                                               "bodies.top_platen.prescribed_velocity=[0.0, -1.0]"};
  add({"contrast-100-dynamic",
       "platens 100x stiffer than the rock, platen 1 m/s",
       flattened,
       stiff_platens,
       std::nullopt,
       200e-6,
       0,
       120.0,
       Expectation::Stable,
       {}});
  auto stiff_static = stiff_platens;
  stiff_static.push_back("analysis.mode=\"static\"");
  add({"contrast-100-static",
       "platens 100x stiffer than the rock, static mode, platen 1 m/s",
       flattened,
       stiff_static,
       std::nullopt,
       200e-6,
       0,
       120.0,
       Expectation::Stable,
       {}});
  // Impossible by construction: the disc moves at 3.5 m/s, so even at the dt floor
  // (dt_max · 1e-6 = 1e-13 s) a step moves it 3.5e-13 m, more than the allowed step displacement
  // 1e-12 × 0.06 m = 6e-14 m. The engine must give up at step 1 with a message, not loop.
  add({"impossible",
       "allowed step displacement (6e-14 m) below v0 x dt floor (3.5e-13 m)",
       impact,
       {impact_blocks, "analysis.max_displacement_ratio=1e-12"},
       std::nullopt,
       100e-6,
       0,
       60.0,
       Expectation::FailsCleanly,
       {"numerical trouble at step 1, t = 0 s", "exceeds the allowed", "even with dt at its floor", "worst: block"}});
  return cases;
}

namespace {

/// The case's engine: its scene with the case's end time, no outputs and no gauges, on the
/// scene's mesh or the sliver slab. Fills the result's mode, aspect ratio, block count and
/// penetration allowance.
std::unique_ptr<dda::Engine> build_case(const StabilityCase& c, const std::filesystem::path& scenes_dir,
                                        StabilityResult& r) {
  std::vector<std::string> overrides = c.overrides;
  overrides.push_back(fmt::format("analysis.end_time={:.17g}", c.end_time));
  overrides.push_back(fmt::format("analysis.output_interval={:.17g}", c.end_time));  // no outputs here
  scene::Scene sc = scene::load_scene(scenes_dir / c.scene, overrides);
  sc.gauges.clear();  // gauges are not measured here (and lie outside a sliver slab)
  r.mode = sc.analysis.mode == scene::Mode::Static ? "static" : "dynamic";
  const meshes::Mesh mesh =
      c.sliver ? make_sliver_slab_mesh(*c.sliver) : meshes::generate_dda_mesh(sc.geometry, sc.mesh);
  r.aspect = max_aspect_ratio(mesh, "disc");
  auto engine = std::make_unique<dda::Engine>(std::move(sc), mesh);
  r.blocks = engine->blocks().block_count();
  r.penetration_allowed = kPenetrationAllowanceFactor * mean_smallest_altitude(engine->blocks());
  const double energy0 = engine->energies().stored();
  r.energy_max = energy0;
  r.supplied_max = energy0;
  return engine;
}

/// One accepted step against the bounds: NaN, stored energy over supplied, penetration. Stop
/// once the step decides the verdict (NaN, or energy above its bound).
dda::Next watch_step(const dda::StepReport& rep, const dda::Engine& e, StabilityResult& r) {
  r.steps = rep.step;
  const double energy = rep.ledger.stored.stored();
  const double supplied = rep.ledger.initial + rep.ledger.work();
  r.balance_error = rep.ledger.largest_balance_error;
  if (!std::isfinite(energy) || !std::isfinite(supplied) || !std::isfinite(rep.max_penetration) ||
      !all_vertices_finite(e.blocks())) {
    r.nan = true;
    r.message = fmt::format(
        "NaN or infinity at step {}, t = {:.9g} s (energy {}, penetration {}) that the engine did "
        "not report",
        rep.step, rep.time, energy, rep.max_penetration);
    return dda::Next::Stop;
  }
  r.energy_max = std::max(r.energy_max, energy);
  r.supplied_max = std::max(r.supplied_max, supplied);
  const double ratio =
      supplied > 0.0 ? energy / supplied : (energy > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  if (ratio > r.energy_ratio) {
    r.energy_ratio = ratio;
    r.energy_ratio_step = rep.step;
  }
  r.penetration_max = std::max(r.penetration_max, rep.max_penetration);
  return ratio <= kEnergyBoundFactor ? dda::Next::Continue : dda::Next::Stop;  // unstable: the verdict is known
}

void record_statistics(const dda::Engine& e, StabilityResult& r) {
  const dda::Statistics& st = e.statistics();
  r.steps = st.steps;
  r.time = e.time();
  r.cuts_displacement = st.cuts_displacement;
  r.cuts_open_close = st.cuts_open_close;
  r.cuts_solver = st.cuts_solver;
  r.dt_min = st.dt_min;
  r.dt_max = st.dt_max;
  r.cracks = e.crack_counts().total;
  r.missed_contacts = st.missed_contacts;
  r.deepest_missed = st.deepest_missed;
}

/// The verdict, and whether it is the one the case expects. `guard`: a step or wall guard
/// stopped the case.
void judge(const StabilityCase& c, bool guard, StabilityResult& r) {
  if (r.exit_status == dda::kRunNumericalTrouble) {
    r.verdict = Verdict::FailedCleanly;
    r.verdict_text = "failed cleanly (exit 3)";
  } else if (r.exit_status != 0) {
    r.verdict = Verdict::Error;
    r.verdict_text = "error: " + r.message;
  } else if (r.nan) {
    r.verdict = Verdict::Unstable;
    r.verdict_text = "unstable: unreported NaN (engine bug)";
  } else if (!(r.energy_ratio <= kEnergyBoundFactor)) {
    r.verdict = Verdict::Unstable;
    r.verdict_text = fmt::format(
        "unstable: energy {:.3g} x supplied at step {}, t = {:.3g} s (the engine reported no "
        "error; {} contact(s) first detected deeper than one step's displacement, deepest {:.3g} m)",
        r.energy_ratio, r.energy_ratio_step, r.time, r.missed_contacts, r.deepest_missed);
  } else if (guard || !r.end_reached) {
    r.verdict = Verdict::DidNotFinish;
    r.verdict_text = "did not finish: " + r.message;
  } else if (r.penetration_max > r.penetration_allowed) {
    r.verdict = Verdict::PenetrationHigh;
    r.verdict_text = fmt::format("stable; penetration {:.2g} x allowance", r.penetration_max / r.penetration_allowed);
  } else {
    r.verdict = Verdict::Stable;
    r.verdict_text = "stable";
  }
  // Penetration above its allowance is an accuracy warning, not instability: such a case still
  // counts as stable for its expectation (the table shows the ratio).
  r.as_expected = c.expect == Expectation::Stable
                      ? (r.verdict == Verdict::Stable || r.verdict == Verdict::PenetrationHigh)
                      : r.verdict == Verdict::FailedCleanly && contains_all(r.message, c.expected_message);
}

}  // namespace

StabilityResult run_stability_case(const StabilityCase& c, const std::filesystem::path& scenes_dir,
                                   const std::function<void(const StabilityProgress&)>& progress,
                                   double progress_every) {
  StabilityResult r;
  r.name = c.name;
  r.extreme = c.extreme;
  r.end_time = c.end_time;
  const double t0 = omp_get_wtime();
  std::unique_ptr<dda::Engine> engine;
  bool guard = false;
  try {
    engine = build_case(c, scenes_dir, r);
    dda::Engine& e = *engine;
    double last_progress = t0;
    dda::DriveHooks hooks;
    hooks.before_step = [&] {
      const double wall = omp_get_wtime() - t0;
      if (r.steps < c.max_steps && !(wall > c.max_wall)) return dda::Next::Continue;
      guard = true;
      r.message =
          r.steps >= c.max_steps
              ? fmt::format("step guard: {} steps reached at t = {:.6g} s of {:.6g} s", r.steps, e.time(), c.end_time)
              : fmt::format("wall guard: {:.0f} s reached at step {}, t = {:.6g} s of {:.6g} s", c.max_wall, r.steps,
                            e.time(), c.end_time);
      return dda::Next::Stop;
    };
    hooks.after_step = [&](const dda::StepReport& rep) {
      if (watch_step(rep, e, r) == dda::Next::Stop) return dda::Next::Stop;
      if (progress && omp_get_wtime() - last_progress >= progress_every) {
        last_progress = omp_get_wtime();
        progress({rep.step, rep.time, c.end_time, last_progress - t0});
      }
      return dda::Next::Continue;
    };
    r.end_reached = dda::drive(e, c.end_time, hooks) == dda::DriveEnd::Reached;
  } catch (const dda::NumericalTrouble& ex) {
    r.exit_status = dda::kRunNumericalTrouble;  // as `ddafrac run`
    r.message = ex.what();
  } catch (const std::exception& ex) {
    r.exit_status = 1;
    r.message = ex.what();
  }
  r.wall = omp_get_wtime() - t0;
  if (engine) record_statistics(*engine, r);
  judge(c, guard, r);
  return r;
}

std::string stability_csv(const std::vector<StabilityResult>& results) {
  std::string out =
      "case,mode,extreme,blocks,aspect,steps,time,end_time,end_reached,nan,energy_max,supplied_max,energy_ratio,"
      "energy_ratio_step,energy_bound_factor,balance_error,penetration_max,penetration_allowed,cuts_displacement,cuts_"
      "open_close,"
      "cuts_solver,dt_min,dt_max,cracks,wall,exit_status,verdict,as_expected,message\n";
  for (const auto& r : results)
    out += fmt::format(
        "{},{},{},{},{:.4g},{},{:.9g},{:.9g},{},{},{:.6g},{:.6g},{:.6g},{},{},{:.3g},{:.6g},{:.6g},{},{},{},{:.6g},"
        "{:.6g},{},{:.3f},{},{},{},{}\n",
        r.name, r.mode, csv_field(r.extreme), r.blocks, r.aspect, r.steps, r.time, r.end_time, r.end_reached ? 1 : 0,
        r.nan ? 1 : 0, r.energy_max, r.supplied_max, r.energy_ratio, r.energy_ratio_step, kEnergyBoundFactor,
        r.balance_error, r.penetration_max, r.penetration_allowed, r.cuts_displacement, r.cuts_open_close,
        r.cuts_solver, r.dt_min, r.dt_max, r.cracks, r.wall, r.exit_status, csv_field(r.verdict_text),
        r.as_expected ? 1 : 0, csv_field(r.message));
  return out;
}

std::string stability_markdown(const std::vector<StabilityResult>& results) {
  std::string out = fmt::format(
      "Energy bound: E(t) ≤ {:.3f} · S(t) at every step, E = kinetic + strain + contact-spring + anchor-spring energy, "
      "S = E(0) + work of gravity, point loads and moving supports so far (the engine's energy ledger). Penetration "
      "allowance: {:.2g} × the mean smallest altitude of the triangular blocks.\n\n",
      kEnergyBoundFactor, kPenetrationAllowanceFactor);
  out +=
      "| case | mode | what is extreme | blocks | steps | end reached | max E/S | balance error | missed contacts | "
      "max "
      "penetration / allowed | dt cuts (displ. / open–close / solver) | open–close failures | min dt (s) | cracks | "
      "wall (s) | "
      "exit | verdict |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : results) {
    const std::string reached = r.end_reached ? "yes" : fmt::format("no (t = {:.3g} s)", r.time);
    const std::string pen = r.penetration_allowed > 0.0
                                ? fmt::format("{:.2e} / {:.2e} m ({:.2g})", r.penetration_max, r.penetration_allowed,
                                              r.penetration_max / r.penetration_allowed)
                                : std::string("–");
    out += fmt::format(
        "| {} | {} | {} | {} | {} | {} | {:.4f} | {:.2e} | {} | {} | {} ({} / {} / {}) | {} | {:.2e} | {} | {:.1f} | "
        "{} | {} |\n",
        r.name, r.mode, md_field(r.extreme), r.blocks, r.steps, reached, r.energy_ratio, r.balance_error,
        r.missed_contacts, pen, r.cuts_displacement + r.cuts_open_close + r.cuts_solver, r.cuts_displacement,
        r.cuts_open_close, r.cuts_solver, r.cuts_open_close, r.dt_min, r.cracks, r.wall, r.exit_status,
        md_field(r.verdict_text));
  }
  bool messages = false;
  for (const auto& r : results)
    if (!r.message.empty()) {
      if (!messages) out += "\nMessages:\n\n";
      messages = true;
      out += fmt::format("- `{}`: {}\n", r.name, r.message);
    }
  return out;
}

}  // namespace ddafrac::coupling
