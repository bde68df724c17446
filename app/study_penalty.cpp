// `ddafrac study penalty [SCENE] --kn-ratios 0.0333,0.1,1,10,100,1000 --dts 1e-6,1e-7,1e-8`:
// the contact-free impact of an impact scene (the comparison of `ddafrac verify`) with the DDA
// twin at every (kn/E, dt) pair against one FEM reference: gauge errors (RMS/peak, peak,
// P-wave arrival), CG iterations, dt cuts and wall time per pair. Writes penalty_study.csv,
// penalty_study.md and penalty_study.png in --out.

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/coupling/impact_compare.hpp"
#include "ddafrac/coupling/impact_runs.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/scene/scene.hpp"
#include "fem_session.hpp"
#include "figures.hpp"
#include "option_checks.hpp"
#include "scene_source.hpp"

namespace ddafrac::app {

namespace {

struct PenaltyArguments {
  SceneArguments scene;
  std::string out;
  std::vector<double> kn_ratios{0.35e9 / 10.53e9, 0.1, 1.0, 10.0, 100.0, 1000.0};
  std::vector<double> dts{1e-6, 1e-7, 1e-8};
  double end_time = 0.0;  // s; 0 = the scene's
  int threads = 1;
  int fem_degree = 2;
  int fem_refine = 0;
  bool no_figures = false;
};

struct Row {
  double ratio = 0.0, dt = 0.0;
  coupling::GaugeHistories dda;
  coupling::ImpactErrorSummary errors;
  std::string status = "ok";
};

std::string csv_header(const std::vector<std::string>& gauges) {
  std::string h =
      "kn_over_E,kn,dt,status,blocks,steps,dt_cuts,cg_total,cg_per_step,cg_max,dda_wall,"
      "predicted_arrival_shift,mean_rms_over_peak,max_rms_over_peak,mean_abs_peak_error,"
      "max_abs_peak_error,max_abs_arrival_error";
  for (const auto& g : gauges) h += fmt::format(",rms_{0},peak_error_{0},arrival_error_{0}", g);
  return h + "\n";
}

/// 1/sqrt(E_eff/E) − 1: how much later the DDA's P wave is expected from the joint compliance.
double predicted_arrival_shift(double ratio) { return 1.0 / std::sqrt(coupling::effective_modulus_ratio(ratio)) - 1.0; }

std::string csv_row(const Row& r) {
  const double per_step =
      r.dda.steps > 0 ? static_cast<double>(r.dda.cg_total) / static_cast<double>(r.dda.steps) : 0.0;
  std::string line = fmt::format("{:.6g},{:.6g},{:.3g},{},{},{},{},{},{:.3f},{},{:.3f},{:.6g}", r.ratio, r.dda.kn, r.dt,
                                 r.status, r.dda.blocks, r.dda.steps, r.dda.dt_cuts, r.dda.cg_total, per_step,
                                 r.dda.cg_max, r.dda.wall, predicted_arrival_shift(r.ratio));
  if (r.status != "ok") {
    line += ",,,,,";
    for (std::size_t g = 0; g < r.dda.names.size(); ++g) line += ",,,";
    return line + "\n";
  }
  const auto& e = r.errors;
  line += fmt::format(",{:.6g},{:.6g},{:.6g},{:.6g},{:.6g}", e.mean_rms, e.max_rms, e.mean_abs_peak, e.max_abs_peak,
                      e.max_abs_arrival);
  for (const auto& g : e.gauges)
    line += fmt::format(",{:.6g},{:.6g},{:.6g}", g.syy.rms_over_peak, g.peak_error, g.arrival_error);
  return line + "\n";
}

std::string markdown(const scene::Scene& s, const coupling::GaugeHistories& fem, const std::vector<Row>& rows,
                     const PenaltyArguments& args) {
  std::ostringstream md;
  md << fmt::format("# Penalty and time-step study: `{}`\n\n", s.name);
  md << fmt::format(
      "DDA twin (bonded, unbreakable virtual joints; impact patch held; no gravity) against the FEM reference (P{}, "
      "{} refinement(s), {} dofs, Newmark (¼, ½), dt = {:.3g} s, {:.1f} s). Errors of σyy over the {} gauges; arrival "
      "(|σyy| at {:.0f}% of ρ c_p v0) checked at the gauges `ddafrac verify` checks; a wave that never arrives counts "
      "as "
      "arriving at the end time. Predicted arrival shift from the joint compliance: sqrt(1 + {:g} E/kn) − 1.\n\n",
      args.fem_degree, args.fem_refine, fem.dofs, fem.dt, fem.wall, fem.names.size(),
      100.0 * coupling::ImpactSettings{}.arrival_fraction, coupling::kJointCompliance);
  md << "| kn/E | dt (s) | blocks | steps | CG/step | dt cuts | DDA wall (s) | predicted arrival shift | mean RMS/peak "
        "| "
        "max RMS/peak | mean abs peak error | max abs arrival error "
        "|\n|---|---|---|---|---|---|---|---|---|---|---|---|\n";
  for (const auto& r : rows) {
    const double per_step =
        r.dda.steps > 0 ? static_cast<double>(r.dda.cg_total) / static_cast<double>(r.dda.steps) : 0.0;
    if (r.status != "ok") {
      md << fmt::format("| {:.4g} | {:.0e} | {} | {} | {:.1f} | {} | {:.1f} | {:+.1f}% | {} |||||\n", r.ratio, r.dt,
                        r.dda.blocks, r.dda.steps, per_step, r.dda.dt_cuts, r.dda.wall,
                        100.0 * predicted_arrival_shift(r.ratio), r.status);
      continue;
    }
    md << fmt::format(
        "| {:.4g} | {:.0e} | {} | {} | {:.1f} | {} | {:.1f} | {:+.1f}% | {:.3f} | {:.3f} | {:.1f}% | {:.1f}% |\n",
        r.ratio, r.dt, r.dda.blocks, r.dda.steps, per_step, r.dda.dt_cuts, r.dda.wall,
        100.0 * predicted_arrival_shift(r.ratio), r.errors.mean_rms, r.errors.max_rms, 100.0 * r.errors.mean_abs_peak,
        100.0 * r.errors.max_abs_arrival);
  }
  md << "\n![errors, CG iterations and wall time against kn/E](penalty_study.png)\n";
  return md.str();
}

void run_penalty_study(const PenaltyArguments& args) {
  const FemSession fem_session;
  const scene::Scene s = args.scene.load();
  const auto out = output_directory(args.out, s, "study_penalty");
  std::filesystem::create_directories(out);

  coupling::ImpactSettings settings;
  settings.end_time = args.end_time;
  settings.threads = args.threads;
  settings.fem_degree = args.fem_degree;
  settings.fem_refine = args.fem_refine;
  fmt::print("penalty study of {}: FEM reference\n", s.name);
  coupling::GaugeHistories fem;
  try {
    fem = coupling::run_impact_fem(s, settings);
  } catch (const std::exception& e) {
    throw CommandFailed(fmt::format("{}: FEM reference: {}", s.source.string(), e.what()));
  }
  fmt::print("  {} dofs, dt = {:.3g} s, {:.1f} s\n", fem.dofs, fem.dt, fem.wall);

  std::vector<Row> rows;
  std::string csv = csv_header(fem.names);
  for (const double dt : args.dts)
    for (const double ratio : args.kn_ratios) {
      Row r;
      r.ratio = ratio;
      r.dt = dt;
      settings.stiffness_ratio = ratio;
      settings.dda_dt = dt;
      try {
        r.dda = coupling::run_impact_dda(s, settings);
        r.errors = coupling::summarise(coupling::compare_gauges(r.dda, fem, settings));
      } catch (const dda::NumericalTrouble& e) {  // a result of the study, not a failure of it
        r.status = "numerical trouble";
        fmt::print("  kn/E = {:.4g}, dt = {:.0e} s: {}\n", ratio, dt, e.what());
      }
      fmt::print(
          "  kn/E = {:<8.4g} dt = {:.0e} s: {} steps, {:.1f} CG/step, {:.1f} s, mean RMS/peak {:.3f}, max "
          "arrival error {:.1f}%\n",
          ratio, dt, r.dda.steps,
          r.dda.steps > 0 ? static_cast<double>(r.dda.cg_total) / static_cast<double>(r.dda.steps) : 0.0, r.dda.wall,
          r.errors.mean_rms, 100.0 * r.errors.max_abs_arrival);
      csv += csv_row(r);
      rows.push_back(std::move(r));
      common::write_whole_text(out / "penalty_study.csv", csv);  // after every pair: a stopped study keeps its rows
    }
  common::write_whole_text(out / "penalty_study.md", markdown(s, fem, rows, args));
  std::fflush(stdout);  // our lines before the plotting script's
  if (!args.no_figures) draw_figures({"penalty-study", out.string()});
  fmt::print("wrote {}\n", (out / "penalty_study.md").string());
}

}  // namespace

void register_study_penalty(CLI::App& study) {
  auto args = std::make_shared<PenaltyArguments>();
  CLI::App* command = study.add_subcommand(
      "penalty", "contact-free impact: DDA twin vs FEM gauge errors, CG iterations and wall time over kn/E and dt");
  args->scene.add_to(*command);
  command->add_option("--out", args->out, "output directory (default runs/<scene name>/study_penalty)");
  command->add_option("--kn-ratios", args->kn_ratios, "joint stiffness kn as multiples of E (comma-separated)")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--dts", args->dts, "DDA time steps dt_max in s (comma-separated)")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--end-time", args->end_time, "simulated time in s (default: the scene's)");
  add_dda_threads_option(*command, args->threads);
  add_fem_degree_option(*command, "--fem-degree", args->fem_degree);
  command->add_option("--fem-refine", args->fem_refine, "uniform refinements of the FEM mesh")
      ->check(CLI::Range(0, 4))
      ->capture_default_str();
  command->add_flag("--no-figures", args->no_figures, "do not draw penalty_study.png");
  command->callback([args] { run_penalty_study(*args); });
}

}  // namespace ddafrac::app
