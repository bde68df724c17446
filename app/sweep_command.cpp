// `ddafrac sweep SWEEP.toml [--out DIR] [--parallel N] [--set key=value ...]`: runs every case
// of a sweep (each as its own `ddafrac run` process, several at once when the cores allow) and
// writes one table of the cases with their crack counts and run times, plus comparison plots.
// With --resume, finished cases are kept and stopped or killed ones continue from their
// checkpoints.

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "case_runs.hpp"
#include "commands.hpp"
#include "ddafrac/common/angles.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/dda/drive.hpp"
#include "ddafrac/scene/parse.hpp"
#include "ddafrac/scene/sweep.hpp"
#include "figures.hpp"
#include "option_checks.hpp"

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;

constexpr double kDegree = common::kRadiansPerDegree;

struct SweepArguments {
  std::string sweep_file;
  std::string out;
  int parallel = 0;
  std::vector<std::string> overrides;
  bool resume = false;                     // keep finished cases, continue stopped ones from their checkpoints
  std::optional<double> checkpoint_every;  // s, passed on to every run (default: run's own)
};

/// Crack counts of a case: total, tensile, shear at the sweep's crack time.
using Cracks = std::optional<std::array<double, 3>>;

/// The impact parameters of a case (θ in degrees, γ, v0 in m/s), if it is an impact scene.
std::string impact_columns(const scene::Scene& s) {
  const auto* impact = std::get_if<meshes::ImpactDisc>(&s.geometry);
  const scene::Body* disc = s.find_body("disc");
  if (!impact || !disc) return ",,";
  const double v0 = std::hypot(disc->initial_velocity[0], disc->initial_velocity[1]);
  return fmt::format("{:g},{:g},{:g}", impact->joint_angle / kDegree, impact->connectivity, v0);
}

/// Crack counts at time t from a run's history.csv: the last row at or before t.
Cracks cracks_at(const fs::path& history, double t) {
  std::ifstream in(history);
  std::string line;
  if (!std::getline(in, line)) return std::nullopt;
  std::map<std::string, std::size_t> column;
  {
    std::stringstream header(line);
    std::string name;
    for (std::size_t i = 0; std::getline(header, name, ','); ++i) column[name] = i;
  }
  for (const char* key : {"t", "cracks_total", "cracks_tensile", "cracks_shear"})
    if (!column.count(key)) return std::nullopt;
  Cracks found;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream row(line);
    for (std::string cell; std::getline(row, cell, ',');) cells.push_back(cell);
    if (cells.size() < column.size()) break;
    if (std::stod(cells[column["t"]]) > t * (1 + dda::kTimeSlack)) break;
    found = {std::stod(cells[column["cracks_total"]]), std::stod(cells[column["cracks_tensile"]]),
             std::stod(cells[column["cracks_shear"]])};
  }
  return found;
}

std::string table_csv(const std::vector<CaseRun>& cases, const std::vector<Cracks>& cracks_of, const fs::path& out) {
  std::string csv =
      "case,scene,theta_deg,gamma,v0,cracks_total,cracks_tensile,cracks_shear,run_time_s,exit_status,run_dir\n";
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const CaseRun& c = cases[k];
    const Cracks& n = cracks_of[k];
    const std::string cracks = n ? fmt::format("{:g},{:g},{:g}", (*n)[0], (*n)[1], (*n)[2]) : ",,";
    csv += fmt::format("{},{},{},{},{:.3f},{},{}\n", c.scene.name, csv_field(c.scene_file.string()),
                       impact_columns(c.scene), cracks, c.wall_seconds, c.exit_code,
                       csv_field(fs::relative(c.run_dir, out).string()));
  }
  return csv;
}

void print_table(const std::vector<CaseRun>& cases, const std::vector<Cracks>& cracks_of, double crack_time) {
  fmt::print("\n{:<18} {:>7} {:>6} {:>6} {:>8} {:>8} {:>8} {:>9}\n", "case", "θ (°)", "γ", "v0", "cracks", "tensile",
             "shear", "time (s)");
  fmt::print("{:<18} {:>6} {:>6} {:>6} {:>8} {:>8} {:>8}\n", "", "", "", "m/s",
             fmt::format("@{:g}µs", crack_time * 1e6), "", "");
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const CaseRun& c = cases[k];
    std::string columns = impact_columns(c.scene);
    std::replace(columns.begin(), columns.end(), ',', ' ');
    std::stringstream parts(columns);
    std::string theta, gamma, v0;
    parts >> theta >> gamma >> v0;
    const auto count = [&](int i) { return cracks_of[k] ? fmt::format("{:g}", (*cracks_of[k])[i]) : std::string("-"); };
    fmt::print("{:<18} {:>6} {:>6} {:>6} {:>8} {:>8} {:>8} {:>9.1f}\n", c.scene.name, theta, gamma, v0, count(0),
               count(1), count(2), c.wall_seconds);
  }
}

void run_sweep(const SweepArguments& args) {
  scene::Sweep sweep;
  try {
    sweep = scene::load_sweep(args.sweep_file);
  } catch (const scene::SceneError& e) {
    throw CommandFailed(e.what());
  }
  std::vector<std::string> overrides = sweep.overrides;
  overrides.insert(overrides.end(), args.overrides.begin(), args.overrides.end());
  const fs::path out = args.out.empty() ? fs::path("runs") / sweep.name : fs::path(args.out);
  std::vector<CaseRun> cases = load_case_runs(sweep.cases, overrides, out, "the sweep's cases");

  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int parallel = args.parallel > 0    ? args.parallel
                       : sweep.parallel > 0 ? sweep.parallel
                                            : std::max(1, cores / sweep.threads);
  fmt::print("sweep {}: {} cases, {} at a time, {} thread(s) each, into {}\n", sweep.name, cases.size(), parallel,
             sweep.threads, out.string());
  fs::create_directories(out);
  if (args.resume)
    for (CaseRun& c : cases) decide_start(c);
  run_cases(cases, {sweep.threads, parallel, args.checkpoint_every, overrides, {}});

  std::vector<Cracks> cracks;
  for (const CaseRun& c : cases) cracks.push_back(cracks_at(c.run_dir / "history.csv", sweep.crack_time));
  const fs::path table = out / "sweep.csv";
  common::write_whole_text(table, table_csv(cases, cracks, out));
  print_table(cases, cracks, sweep.crack_time);
  fmt::print("\nwrote {}\n", table.string());
  std::fflush(stdout);  // before the plotting script prints to the same terminal
  draw_figures({"sweep", table.string(), "--out", (out / "figures").string()});

  const auto failed = std::count_if(cases.begin(), cases.end(), [](const CaseRun& c) { return c.exit_code != 0; });
  if (failed > 0) throw CommandFailed(fmt::format("{} of {} cases failed (see their run.log)", failed, cases.size()));
}

}  // namespace

void register_sweep_command(CLI::App& app) {
  auto args = std::make_shared<SweepArguments>();
  CLI::App* command = app.add_subcommand("sweep", "run a set of cases (a sweep file) and tabulate their cracks");
  command->add_option("sweep", args->sweep_file, "sweep file (TOML), e.g. scenes/impact/cases.sweep.toml")->required();
  command->add_option("--out", args->out, "output directory (default runs/<sweep name>)");
  command->add_option("--parallel", args->parallel, "runs at once (default: cores / threads per run)")
      ->check(whole_number(1, kMaxParallelRuns));
  command->add_option("--set", args->overrides, "override a value of every case, e.g. --set mesh.blocks=1200")
      ->type_name("KEY=VALUE");
  command
      ->add_option("--checkpoint-every", args->checkpoint_every,
                   "wall seconds between the checkpoints of each run (default: that of ddafrac run)")
      ->check(non_negative_number());
  command->add_flag("--resume", args->resume,
                    "keep the cases that finished with the scene they have now, continue stopped or killed ones from "
                    "their checkpoints, run the rest");
  command->callback([args] { run_sweep(*args); });
}

}  // namespace ddafrac::app
