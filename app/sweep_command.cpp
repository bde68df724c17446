// `ddafrac sweep SWEEP.toml [--out DIR] [--parallel N] [--set key=value ...]`: runs every case
// of a sweep (each as its own `ddafrac run` process, several at once when the cores allow) and
// writes one table of the cases with their crack counts and run times, plus comparison plots.
// With --resume, finished cases are kept and stopped or killed ones continue from their
// checkpoints.

#include <CLI/CLI.hpp>
#include <fmt/core.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "commands.hpp"
#include "option_checks.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/dda/checkpoint.hpp"
#include "ddafrac/dda/drive.hpp"
#include "ddafrac/dda/run.hpp"
#include "ddafrac/scene/parse.hpp"
#include "ddafrac/scene/sweep.hpp"
#include "figures.hpp"
#include "subprocess.hpp"
#include "ddafrac/common/angles.hpp"

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

constexpr double kDegree = common::kRadiansPerDegree;

struct SweepArguments {
  std::string sweep_file;
  std::string out;
  int parallel = 0;
  std::vector<std::string> overrides;
  bool resume = false;  // keep finished cases, continue stopped ones from their checkpoints
  std::optional<double> checkpoint_every;  // s, passed on to every run (default: run's own)
};

/// How a case starts: from t = 0, from its checkpoint, or not at all (finished before).
enum class Start { Fresh, FromCheckpoint, Finished };

/// One case: its scene (validated before anything runs) and, once run, its results.
struct Case {
  fs::path scene_file;
  scene::Scene scene;
  fs::path run_dir;
  Start start = Start::Fresh;
  int exit_code = -1;
  double wall_seconds = 0.0;
  std::optional<std::array<double, 3>> cracks;  // total, tensile, shear at the sweep's crack time
};

/// The impact parameters of a case (θ in degrees, γ, v0 in m/s), if it is an impact scene.
std::string impact_columns(const scene::Scene& s) {
  const auto* impact = std::get_if<meshes::ImpactDisc>(&s.geometry);
  const scene::Body* disc = s.find_body("disc");
  if (!impact || !disc) return ",,";
  const double v0 = std::hypot(disc->initial_velocity[0], disc->initial_velocity[1]);
  return fmt::format("{:g},{:g},{:g}", impact->joint_angle / kDegree, impact->connectivity, v0);
}

/// Crack counts at time t from a run's history.csv: the last row at or before t.
std::optional<std::array<double, 3>> cracks_at(const fs::path& history, double t) {
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
  std::optional<std::array<double, 3>> found;
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

/// Each case runs in the folder of its scene name: two cases of one name would overwrite each
/// other's run, so they are refused before anything runs.
void refuse_shared_names(const std::vector<Case>& cases) {
  std::map<std::string, std::vector<std::string>> files_of;
  for (const Case& c : cases) files_of[c.scene.name].push_back(c.scene_file.string());
  std::string problems;
  for (const auto& [name, files] : files_of)
    if (files.size() > 1) problems += fmt::format("\n  \"{}\": {}", name, fmt::join(files, ", "));
  if (!problems.empty())
    throw CommandFailed("cases share a scene name, so their runs would overwrite each other (nothing was run; give "
                        "each a name = \"...\"):" + problems);
}

/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + '"';
}

std::vector<Case> load_cases(const scene::Sweep& sweep, const std::vector<std::string>& overrides, const fs::path& out) {
  std::vector<Case> cases;
  std::string problems;
  for (const fs::path& file : sweep.cases) {
    try {
      Case c;
      c.scene_file = file;
      c.scene = scene::load_scene(file, overrides);
      c.run_dir = out / c.scene.name;
      cases.push_back(std::move(c));
    } catch (const scene::SceneError& e) {
      problems += fmt::format("\n{}: {}", file.string(), e.what());
    }
  }
  if (!problems.empty()) throw CommandFailed("the sweep's cases have problems (nothing was run):" + problems);
  refuse_shared_names(cases);
  return cases;
}

std::vector<std::string> run_arguments(const Case& c, const scene::Sweep& sweep, const SweepArguments& args,
                                       const std::vector<std::string>& overrides) {
  std::vector<std::string> argv{own_executable().string(), "run", "--threads", std::to_string(sweep.threads)};
  if (args.checkpoint_every) {
    argv.push_back("--checkpoint-every");
    argv.push_back(fmt::format("{:.17g}", *args.checkpoint_every));
  }
  if (c.start == Start::FromCheckpoint) {
    argv.push_back("--resume");
    argv.push_back(c.run_dir.string());
    return argv;
  }
  for (const std::string& item : {c.scene_file.string(), std::string("--out"), c.run_dir.string()}) argv.push_back(item);
  for (const std::string& o : overrides) {
    argv.push_back("--set");
    argv.push_back(o);
  }
  return argv;
}

/// The text of a file, or nothing if it cannot be read.
std::optional<std::string> file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

/// A run's summary.json, or a discarded value if it cannot be read.
nlohmann::json read_summary(const fs::path& run_dir) {
  std::ifstream in(run_dir / "summary.json");
  return nlohmann::json::parse(in, nullptr, false);
}

/// A run's wall time over all its parts (a resumed run's included), from its summary.json.
std::optional<double> summary_wall(const nlohmann::json& summary) {
  if (summary.is_discarded() || !summary.contains("wall_time")) return std::nullopt;
  return summary["wall_time"].value("total", 0.0);
}

/// For a resumed sweep: a case whose run completed with the scene it has now is finished (its
/// wall time is the run's); one with a checkpoint of that scene continues from it; any other
/// (never started, failed, or its scene changed since) starts again from t = 0.
void decide_start(Case& c) {
  const nlohmann::json summary = read_summary(c.run_dir);
  const bool same_scene = file_text(c.run_dir / dda::kResolvedSceneFile) == c.scene.resolved_text;
  if (same_scene && !summary.is_discarded() && summary.contains("exit") &&
      summary["exit"].value("reason", "") == "completed") {
    c.start = Start::Finished;
    c.exit_code = 0;
    c.wall_seconds = summary_wall(summary).value_or(0.0);
    return;
  }
  if (same_scene && fs::exists(c.run_dir / dda::kCheckpointFile)) {
    c.start = Start::FromCheckpoint;
    return;
  }
  c.start = Start::Fresh;
}

/// Runs the cases, `parallel` at a time, and records exit codes and wall times.
void run_cases(std::vector<Case>& cases, const scene::Sweep& sweep, const SweepArguments& args,
               const std::vector<std::string>& overrides, int parallel) {
  std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
  std::size_t next = 0, done = 0;
  while (done < cases.size()) {
    while (next < cases.size() && static_cast<int>(running.size()) < parallel) {
      Case& c = cases[next++];
      if (c.start == Start::Finished) {
        fmt::print("[{}/{}] {} finished before (kept)\n", ++done, cases.size(), c.scene.name);
        continue;
      }
      fs::create_directories(c.run_dir);
      const fs::path log = c.run_dir / "run.log";
      // A resumed run's log goes on after the stopped one's.
      if (c.start == Start::Fresh) fs::remove(log);
      running[spawn_process(run_arguments(c, sweep, args, overrides), log)] = {next - 1, Clock::now()};
      fmt::print("{} {} ({})\n", c.start == Start::FromCheckpoint ? "resumed " : "started ", c.scene.name,
                 c.scene_file.string());
    }
    if (done == cases.size()) break;
    const Finished finished = wait_for_any_child();
    const auto it = running.find(finished.pid);
    if (it == running.end()) continue;
    Case& c = cases[it->second.first];
    c.exit_code = finished.exit_code;
    c.wall_seconds = std::chrono::duration<double>(Clock::now() - it->second.second).count();
    running.erase(it);
    ++done;
    fmt::print("[{}/{}] {} {} in {:.1f} s{}\n", done, cases.size(), c.scene.name,
               c.exit_code == 0 ? "finished" : "FAILED", c.wall_seconds,
               c.exit_code == 0 ? "" : fmt::format(" (exit status {}; see {})", c.exit_code, (c.run_dir / "run.log").string()));
    std::fflush(stdout);
  }
}

std::string table_csv(const std::vector<Case>& cases, const fs::path& out) {
  std::string csv = "case,scene,theta_deg,gamma,v0,cracks_total,cracks_tensile,cracks_shear,run_time_s,exit_status,run_dir\n";
  for (const Case& c : cases) {
    const std::string cracks =
        c.cracks ? fmt::format("{:g},{:g},{:g}", (*c.cracks)[0], (*c.cracks)[1], (*c.cracks)[2]) : ",,";
    csv += fmt::format("{},{},{},{},{:.3f},{},{}\n", c.scene.name, csv_field(c.scene_file.string()),
                       impact_columns(c.scene), cracks, c.wall_seconds, c.exit_code,
                       csv_field(fs::relative(c.run_dir, out).string()));
  }
  return csv;
}

void print_table(const std::vector<Case>& cases, double crack_time) {
  fmt::print("\n{:<18} {:>7} {:>6} {:>6} {:>8} {:>8} {:>8} {:>9}\n", "case", "θ (°)", "γ", "v0", "cracks", "tensile",
             "shear", "time (s)");
  fmt::print("{:<18} {:>6} {:>6} {:>6} {:>8} {:>8} {:>8}\n", "", "", "", "m/s",
             fmt::format("@{:g}µs", crack_time * 1e6), "", "");
  for (const Case& c : cases) {
    std::string columns = impact_columns(c.scene);
    std::replace(columns.begin(), columns.end(), ',', ' ');
    std::stringstream parts(columns);
    std::string theta, gamma, v0;
    parts >> theta >> gamma >> v0;
    const auto count = [&](int i) { return c.cracks ? fmt::format("{:g}", (*c.cracks)[i]) : std::string("-"); };
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
  std::vector<Case> cases = load_cases(sweep, overrides, out);

  const int cores = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int parallel = args.parallel > 0 ? args.parallel
                       : sweep.parallel > 0 ? sweep.parallel
                                            : std::max(1, cores / sweep.threads);
  fmt::print("sweep {}: {} cases, {} at a time, {} thread(s) each, into {}\n", sweep.name, cases.size(), parallel,
             sweep.threads, out.string());
  fs::create_directories(out);
  if (args.resume)
    for (Case& c : cases) decide_start(c);
  run_cases(cases, sweep, args, overrides, parallel);
  // A resumed case took the time of all its parts.
  for (Case& c : cases)
    if (c.start == Start::FromCheckpoint) c.wall_seconds = summary_wall(read_summary(c.run_dir)).value_or(c.wall_seconds);

  for (Case& c : cases) c.cracks = cracks_at(c.run_dir / "history.csv", sweep.crack_time);
  const fs::path table = out / "sweep.csv";
  common::write_whole_text(table, table_csv(cases, out));
  print_table(cases, sweep.crack_time);
  fmt::print("\nwrote {}\n", table.string());
  std::fflush(stdout);  // before the plotting script prints to the same terminal
  draw_figures({"sweep", table.string(), "--out", (out / "figures").string()});

  const auto failed = std::count_if(cases.begin(), cases.end(), [](const Case& c) { return c.exit_code != 0; });
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
  command->add_option("--checkpoint-every", args->checkpoint_every,
                      "wall seconds between the checkpoints of each run (default: that of ddafrac run)")
      ->check(non_negative_number());
  command->add_flag("--resume", args->resume,
                    "keep the cases that finished with the scene they have now, continue stopped or killed ones from "
                    "their checkpoints, run the rest");
  command->callback([args] { run_sweep(*args); });
}

}  // namespace ddafrac::app
