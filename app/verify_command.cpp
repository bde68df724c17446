// `ddafrac verify SCENE [--out DIR] [--threads N] [--set key=value ...] [--degree p] [--refine k]`:
// the scene run by the DDA twin of the continuum (bonded, unbreakable virtual joints) and by the
// FEM reference (and the analytic solution where one exists), compared against the tolerances
// of the scene's [verification] table. Writes verification.md, summary.json, the comparison's
// CSV files and PNG plots; exit status 0 on PASS, 1 on FAIL.

#include "verify_command.hpp"

#include <fmt/core.h>
#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "commands.hpp"
#include "ddafrac/build_commit.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/coupling/verify.hpp"
#include "fem_session.hpp"
#include "figures.hpp"
#include "option_checks.hpp"
#include "scene_source.hpp"

namespace ddafrac::app {

namespace {

struct VerifyArguments {
  SceneArguments scene;
  std::string out;
  int threads = 1;
  int degree = 2;
  int refine = 1;
  double stiffness_ratio = 100.0;
  bool no_figures = false;
};

std::string utc_now() {
  const std::time_t t = std::time(nullptr);
  char buf[32];
  std::strftime(buf, sizeof buf, "%Y-%m-%d %H:%M:%S UTC", std::gmtime(&t));
  return buf;
}

void run_verify(const VerifyArguments& args) {
  const FemSession fem_session;
  const scene::Scene s = args.scene.load();
  coupling::VerifyOptions options;
  options.out_dir = output_directory(args.out, s, "verify");
  options.threads = args.threads;
  options.fem_degree = args.degree;
  options.fem_refine = args.refine;
  options.stiffness_ratio = args.stiffness_ratio;
  options.figures = !args.no_figures;
  const auto report = verify_and_report(s, options);
  if (!report.passed())
    throw CommandFailed(
        fmt::format("verification FAILED ({}): see {}", s.name, (options.out_dir / "verification.md").string()), 1);
}

}  // namespace

coupling::VerificationReport verify_and_report(const scene::Scene& s, const coupling::VerifyOptions& options) {
  const auto missing = coupling::missing_tolerances(s);
  if (!missing.empty()) {
    std::string list;
    for (const auto& m : missing) list += (list.empty() ? "" : ", ") + m;
    throw CommandFailed(
        fmt::format("{}: cannot verify this scene: it does not set {} (add a [verification] table with the "
                    "tolerances; see README, Scene files)",
                    s.source.empty() ? s.name : s.source.string(), list));
  }
  std::filesystem::create_directories(options.out_dir);
  coupling::VerificationReport report;
  try {
    report = coupling::verify_scene(s, options);
  } catch (const std::invalid_argument& e) {
    throw CommandFailed(e.what());
  }
  bool figures = false;
  if (options.figures)  // the impact comparison writes impact_gauges.csv, the static one profiles.csv
    figures = draw_figures({std::filesystem::exists(options.out_dir / "impact_gauges.csv") ? "verify-impact" : "verify",
                            options.out_dir.string()});

  std::ostringstream md;
  md << "# Verification: " << s.name << "\n\n";
  md << fmt::format("Scene `{}`{}; ddafrac {} (commit {}, {}), {}; {} DDA thread(s) (results do not depend on it).\n\n",
                    s.source.string(), s.description.empty() ? "" : " — " + s.description, DDAFRAC_VERSION,
                    DDAFRAC_COMMIT, DDAFRAC_ARCH, utc_now(), options.threads);
  md << fmt::format("Run times: DDA {:.2f} s, FEM {:.2f} s.\n\n", report.dda_wall, report.fem_wall);
  md << report.markdown;
  if (options.figures && !figures)
    md << "(The PNG figures could not be drawn: matplotlib missing; the CSV files are complete.)\n\n";
  md << "## Checks (tolerances from the scene's [verification] table)\n\n| check | measured | tolerance | key | "
        "|\n|---|---|---|---|---|\n";
  for (const auto& c : report.checks)
    md << fmt::format("| {} | {:.4g} | {:.4g} | `verification.{}` | {} |\n", c.what, c.value, c.tolerance, c.key,
                      c.passed() ? "pass" : "**FAIL**");
  md << "\n";
  std::string line = report.passed() ? "PASS" : "FAIL";
  for (const auto& c : report.checks)
    line += fmt::format("; {} {:.3g} {} {:.3g}", c.what, c.value, c.passed() ? "<=" : ">", c.tolerance);
  if (report.checks.empty()) line += "; no checks were made";
  md << "**" << line << "**\n";
  common::write_whole_text(options.out_dir / "verification.md", md.str());

  nlohmann::json summary{{"scene", s.name},
                         {"scene_file", s.source.string()},
                         {"version", DDAFRAC_VERSION},
                         {"commit", DDAFRAC_COMMIT},
                         {"arch", DDAFRAC_ARCH},
                         {"threads", options.threads},
                         {"fem_degree", options.fem_degree},
                         {"fem_refine", options.fem_refine},
                         {"stiffness_ratio", options.stiffness_ratio},
                         {"title", report.title},
                         {"dda_wall", report.dda_wall},
                         {"fem_wall", report.fem_wall},
                         {"passed", report.passed()}};
  summary["checks"] = nlohmann::json::array();
  for (const auto& c : report.checks)
    summary["checks"].push_back(
        {{"what", c.what}, {"key", c.key}, {"value", c.value}, {"tolerance", c.tolerance}, {"passed", c.passed()}});
  const auto comparison = options.out_dir / "comparison.json";
  if (std::filesystem::exists(comparison)) {
    std::ifstream in(comparison);
    summary["comparison"] = nlohmann::json::parse(in, nullptr, false);
  }
  common::write_whole_text(options.out_dir / "summary.json", summary.dump(2) + "\n");
  if (!options.quiet) {
    fmt::print("{}\n", line);
    fmt::print("wrote {}\n", (options.out_dir / "verification.md").string());
  }
  return report;
}

void register_verify_command(CLI::App& app) {
  auto args = std::make_shared<VerifyArguments>();
  CLI::App* command = app.add_subcommand("verify",
                                         "DDA (bonded, unbreakable joints) vs FEM (and analytic) on the scene; "
                                         "PASS/FAIL against its [verification] tolerances");
  args->scene.add_to(*command);
  command->add_option("--out", args->out, "output directory (default runs/<scene name>/verify)");
  add_dda_threads_option(*command, args->threads);
  add_fem_degree_option(*command, "--degree", args->degree);
  command->add_option("--refine", args->refine, "uniform refinements of the FEM mesh (element size D/25)")
      ->check(CLI::Range(0, 5))
      ->capture_default_str();
  command
      ->add_option("--stiffness-ratio", args->stiffness_ratio,
                   "DDA joint stiffness kn as a multiple of E (each joint set keeps its ks/kn); <= 0 keeps the scene's")
      ->capture_default_str();
  command->add_flag("--no-figures", args->no_figures, "do not draw the PNG plots");
  command->callback([args] { run_verify(*args); });
}

}  // namespace ddafrac::app
