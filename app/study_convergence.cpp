// `ddafrac study convergence SCENE --blocks 500,1000,2000 [--fem-refine k] [--out DIR]`: the
// same comparison as `ddafrac verify` at several DDA block counts; one row per level (blocks,
// steps, DDA and FEM wall time, every error of the comparison), convergence.csv, a log-log PNG
// of error against DDA wall time, and the observed rate (least-squares slope of log error
// against log h with h ~ 1/sqrt(blocks)).

#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/coupling/verify.hpp"
#include "fem_session.hpp"
#include "figures.hpp"
#include "option_checks.hpp"
#include "scene_source.hpp"
#include "verify_command.hpp"

namespace ddafrac::app {

namespace {

struct ConvergenceArguments {
  SceneArguments scene;
  std::string out;
  std::vector<int> blocks{500, 1000, 2000, 4000};
  int threads = 1;
  int degree = 2;
  std::vector<int> fem_refine{1};  // one value for every level, or one per level
  double stiffness_ratio = 100.0;
  bool no_figures = false;
};

struct Level {
  int target = 0;
  long blocks = 0, steps = 0;
  int fem_refine = 0;
  long fem_dofs = 0;
  double fem_vs_analytic = std::nan("");  // field L2 of the FEM against the analytic solution, if any
  double inner = std::nan("");            // static: DDA vs FEM field L2 over r < 0.8 R
  double dda_wall = 0.0, fem_wall = 0.0;
  bool passed = false;
  std::vector<double> errors;  // one per check, in the order of the first level's checks
};

/// Least-squares slope of y against x.
double slope(const std::vector<double>& x, const std::vector<double>& y) {
  const double n = static_cast<double>(x.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    sx += x[i];
    sy += y[i];
    sxx += x[i] * x[i];
    sxy += x[i] * y[i];
  }
  return (n * sxy - sx * sy) / (n * sxx - sx * sx);
}

std::string csv_name(std::string what) {
  for (char& c : what)
    if (c == ',') c = ';';
  return what;
}

void run_convergence(const ConvergenceArguments& args) {
  const FemSession fem_session;
  const scene::Scene base = args.scene.load();
  const auto out = output_directory(args.out, base, "convergence");
  std::filesystem::create_directories(out);
  if (args.fem_refine.size() != 1 && args.fem_refine.size() != args.blocks.size())
    throw CommandFailed(fmt::format("--fem-refine takes one value or one per level ({} levels, {} values)",
                                    args.blocks.size(), args.fem_refine.size()));
  std::vector<Level> levels;
  std::vector<std::string> names;
  for (std::size_t index = 0; index < args.blocks.size(); ++index) {
    const int target = args.blocks[index];
    scene::Scene s = base;
    s.mesh.target_blocks = target;
    coupling::VerifyOptions options;
    options.out_dir = out / fmt::format("blocks_{}", target);
    options.threads = args.threads;
    options.fem_degree = args.degree;
    options.fem_refine = args.fem_refine.size() == 1 ? args.fem_refine[0] : args.fem_refine[index];
    options.stiffness_ratio = args.stiffness_ratio;
    options.figures = !args.no_figures;
    options.quiet = true;
    fmt::print("level {} blocks ...\n", target);
    std::fflush(stdout);
    const auto report = verify_and_report(s, options);
    Level level;
    level.target = target;
    level.blocks = target;
    level.dda_wall = report.dda_wall;
    level.fem_wall = report.fem_wall;
    level.passed = report.passed();
    level.fem_refine = options.fem_refine;
    std::ifstream in(options.out_dir / "comparison.json");
    if (in) {
      const auto j = nlohmann::json::parse(in, nullptr, false);
      if (j.is_object()) {
        level.blocks = j.value("blocks", static_cast<long>(target));
        level.steps = j.value("steps", 0L);
        level.fem_dofs = j.value("fem_dofs", 0L);
        level.fem_vs_analytic = j.value("field_l2_fem_vs_analytic", std::nan(""));
        level.inner = j.value("field_l2_fem_inner", std::nan(""));
      }
    }
    const std::string inner_name = "field L2 (sxx, syy, txy) over r < 0.8 R, DDA vs FEM";
    if (names.empty()) {
      for (const auto& c : report.checks) names.push_back(c.what);
      if (!std::isnan(level.inner)) names.push_back(inner_name);
    }
    for (const auto& n : names) {
      double v = n == inner_name ? level.inner : std::nan("");
      for (const auto& c : report.checks)
        if (c.what == n) v = std::max(std::isnan(v) ? 0.0 : v, c.value);
      level.errors.push_back(v);
    }
    fmt::print("  {} blocks, {} steps, DDA {:.2f} s, FEM {:.2f} s, {}\n", level.blocks, level.steps, level.dda_wall,
               level.fem_wall, level.passed ? "pass" : "fail");
    std::fflush(stdout);
    levels.push_back(level);
  }

  // Observed rates: slope of log error against log h, h = 1/sqrt(blocks), and against wall time.
  std::vector<double> rate_h(names.size(), std::nan("")), rate_t(names.size(), std::nan(""));
  if (levels.size() >= 2)
    for (std::size_t k = 0; k < names.size(); ++k) {
      std::vector<double> lh, lt, le;
      for (const auto& l : levels)
        if (l.errors[k] > 0.0) {
          lh.push_back(std::log(1.0 / std::sqrt(static_cast<double>(l.blocks))));
          lt.push_back(std::log(l.dda_wall));
          le.push_back(std::log(l.errors[k]));
        }
      if (le.size() >= 2) {
        rate_h[k] = slope(lh, le);
        rate_t[k] = slope(lt, le);
      }
    }

  std::ostringstream csv;
  csv << "target,blocks,steps,dda_wall,fem_refine,fem_dofs,fem_wall,fem_l2_vs_analytic,passed";
  for (const auto& n : names) csv << "," << csv_name(n);
  csv << "\n";
  for (const auto& l : levels) {
    csv << fmt::format("{},{},{},{:.6g},{},{},{:.6g},{:.6g},{}", l.target, l.blocks, l.steps, l.dda_wall, l.fem_refine,
                       l.fem_dofs, l.fem_wall, l.fem_vs_analytic, l.passed ? 1 : 0);
    for (const double e : l.errors) csv << fmt::format(",{:.6g}", e);
    csv << "\n";
  }
  common::write_whole_text(out / "convergence.csv", csv.str());

  std::ostringstream md;
  md << fmt::format(
      "# Convergence: {}\n\nScene `{}`; DDA kn = {}·E; FEM P{} (refinements per level in the table); {} thread(s).\n\n",
      base.name, base.source.string(), args.stiffness_ratio, args.degree, args.threads);
  md << "| blocks | steps | DDA wall (s) | FEM k | FEM dofs | FEM wall (s) | FEM vs analytic |";
  for (const auto& n : names) md << " " << n << " |";
  md << "\n|---|---|---|---|---|---|---|";
  for (std::size_t k = 0; k < names.size(); ++k) md << "---|";
  md << "\n";
  for (const auto& l : levels) {
    md << fmt::format("| {} | {} | {:.2f} | {} | {} | {:.2f} | {:.4f} |", l.blocks, l.steps, l.dda_wall, l.fem_refine,
                      l.fem_dofs, l.fem_wall, l.fem_vs_analytic);
    for (const double e : l.errors) md << fmt::format(" {:.4f} |", e);
    md << "\n";
  }
  md << "\nObserved rates (least-squares slope of log error against log h, h ~ 1/sqrt(blocks); and against log DDA "
        "wall time):\n\n";
  for (std::size_t k = 0; k < names.size(); ++k)
    md << fmt::format("- {}: {:.2f} in h, {:.2f} in wall time\n", names[k], rate_h[k], rate_t[k]);
  md << "\n![error against DDA wall time](convergence.png)\n";
  common::write_whole_text(out / "convergence.md", md.str());
  fmt::print("{}", md.str());
  if (!args.no_figures)
    draw_figures({"convergence", (out / "convergence.csv").string(), (out / "convergence.png").string()});
  fmt::print("wrote {}\n", out.string());
}

}  // namespace

void register_study_convergence(CLI::App& study) {
  auto args = std::make_shared<ConvergenceArguments>();
  CLI::App* command = study.add_subcommand(
      "convergence",
      "the verify comparison at several DDA block counts: error against run time, observed convergence rate");
  args->scene.add_to(*command);
  command->add_option("--blocks", args->blocks, "DDA block counts, e.g. 500,1000,2000,4000")
      ->delimiter(',')
      ->capture_default_str();
  command->add_option("--out", args->out, "output directory (default runs/<scene name>/convergence)");
  add_dda_threads_option(*command, args->threads);
  add_fem_degree_option(*command, "--degree", args->degree);
  command
      ->add_option("--fem-refine", args->fem_refine,
                   "uniform refinements of the FEM reference: one value, or one per level (e.g. 0,0,1,1,2)")
      ->delimiter(',')
      ->check(CLI::Range(0, 5))
      ->capture_default_str();
  command->add_option("--stiffness-ratio", args->stiffness_ratio, "DDA joint stiffness kn as a multiple of E")
      ->capture_default_str();
  command->add_flag("--no-figures", args->no_figures, "do not draw the PNG plots");
  command->callback([args] { run_convergence(*args); });
}

}  // namespace ddafrac::app
