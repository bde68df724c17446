// `ddafrac sweep SWEEP.toml [--out DIR] [--parallel N] [--set key=value ...]`: runs every case
// of a sweep (each as its own `ddafrac run` process, several at once when the cores allow) and
// writes one table of the cases with their crack counts and run times, plus comparison plots.
// With --resume, finished cases are kept and stopped or killed ones continue from their
// checkpoints. Under `mpirun`/`srun` the cases are spread over the ranks (case_ranks.hpp).
// `--emit-slurm` writes a Slurm job array of the cases instead of running them, and
// `ddafrac sweep --collect DIR` tabulates whatever cases of DIR have finished.

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <thread>

#include "case_ranks.hpp"
#include "case_runs.hpp"
#include "commands.hpp"
#include "ddafrac/common/angles.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/dda/checkpoint.hpp"
#include "ddafrac/dda/drive.hpp"
#include "ddafrac/scene/parse.hpp"
#include "ddafrac/scene/sweep.hpp"
#include "figures.hpp"
#include "option_checks.hpp"
#include "subprocess.hpp"

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;

constexpr double kDegree = common::kRadiansPerDegree;
constexpr const char* kTableFile = "sweep.csv";
constexpr const char* kRecordFile = "sweep.json";        // the sweep file and --set values, for --collect
constexpr const char* kSlurmScriptFile = "sweep.slurm";  // the job array of --emit-slurm
constexpr const char* kExitStatusFile = "exit_status";   // a job array task's run's, in its run directory

struct SweepArguments {
  std::string sweep_file;
  std::string out;
  int parallel = 0;
  std::vector<std::string> overrides;
  bool resume = false;                     // keep finished cases, continue stopped ones from their checkpoints
  std::optional<double> checkpoint_every;  // s, passed on to every run (default: run's own)
  bool emit_slurm = false;                 // write a Slurm job array of the cases instead of running them
  std::string collect;                     // a sweep's output directory to tabulate as it stands
};

/// A sweep with its cases loaded: what running, emitting and collecting share.
struct LoadedSweep {
  scene::Sweep sweep;
  std::vector<std::string> command_overrides;  // the --set values given on the command line
  std::vector<std::string> overrides;          // the sweep file's, then the command line's
  fs::path out;
  std::vector<CaseRun> cases;
};

LoadedSweep load(const fs::path& sweep_file, const std::vector<std::string>& command_overrides,
                 const std::string& out) {
  LoadedSweep loaded;
  try {
    loaded.sweep = scene::load_sweep(sweep_file);
  } catch (const scene::SceneError& e) {
    throw CommandFailed(e.what());
  }
  loaded.command_overrides = command_overrides;
  loaded.overrides = loaded.sweep.overrides;
  loaded.overrides.insert(loaded.overrides.end(), command_overrides.begin(), command_overrides.end());
  loaded.out = out.empty() ? fs::path("runs") / loaded.sweep.name : fs::path(out);
  loaded.cases = load_case_runs(loaded.sweep.cases, loaded.overrides, loaded.out, "the sweep's cases");
  return loaded;
}

/// sweep.json in the output directory: what --collect needs to know the cases again.
void write_record(const LoadedSweep& s) {
  const nlohmann::json record{{"sweep", fs::absolute(s.sweep.source).string()}, {"set", s.command_overrides}};
  common::write_whole_text(s.out / kRecordFile, record.dump(2) + "\n");
}

LoadedSweep load_recorded(const fs::path& out) {
  const auto text = file_text(out / kRecordFile);
  const nlohmann::json record = text ? nlohmann::json::parse(*text, nullptr, false) : nlohmann::json();
  if (!record.is_object() || !record.contains("sweep") || !record.contains("set"))
    throw CommandFailed(fmt::format(
        "sweep --collect: {} holds no sweep ({} is missing or damaged; `ddafrac sweep` and --emit-slurm write it)",
        out.string(), kRecordFile));
  return load(record["sweep"].get<std::string>(), record["set"].get<std::vector<std::string>>(), out.string());
}

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

/// Where a case stands: done, failed (its run's exit status, or its summary, says so), not
/// started (no summary), or unfinished (running, or stopped: a resume continues it).
std::string case_state(const CaseRun& c) {
  if (c.exit_code == 0) return "done";
  if (c.exit_code > 0) return "failed";
  const nlohmann::json summary = read_summary(c.run_dir);
  if (summary.is_discarded()) return "not started";
  const std::string reason = summary.contains("exit") ? summary["exit"].value("reason", "") : "";
  return reason == "numerical_trouble" || reason == "write_failed" ? "failed" : "unfinished";
}

/// Crack counts of the cases whose runs ended (an unfinished run's counts would be of another time).
std::vector<Cracks> ended_cracks(const std::vector<CaseRun>& cases, double crack_time) {
  std::vector<Cracks> cracks;
  for (const CaseRun& c : cases) {
    const std::string state = case_state(c);
    cracks.push_back(state == "done" || state == "failed" ? cracks_at(c.run_dir / "history.csv", crack_time)
                                                          : std::nullopt);
  }
  return cracks;
}

std::string table_csv(const std::vector<CaseRun>& cases, const std::vector<Cracks>& cracks_of, const fs::path& out) {
  std::string csv =
      "case,scene,theta_deg,gamma,v0,cracks_total,cracks_tensile,cracks_shear,run_time_s,exit_status,run_dir,state,"
      "expected_block_steps\n";
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const CaseRun& c = cases[k];
    const Cracks& n = cracks_of[k];
    const std::string cracks = n ? fmt::format("{:g},{:g},{:g}", (*n)[0], (*n)[1], (*n)[2]) : ",,";
    const std::string exit_status = c.exit_code >= 0 ? std::to_string(c.exit_code) : "";
    csv += fmt::format("{},{},{},{},{:.3f},{},{},{},{:.4g}\n", c.scene.name, csv_field(c.scene_file.string()),
                       impact_columns(c.scene), cracks, c.wall_seconds, exit_status,
                       csv_field(fs::relative(c.run_dir, out).string()), case_state(c), expected_cost(c.scene));
  }
  return csv;
}

/// Writes sweep.csv; returns the crack counts it holds.
std::vector<Cracks> write_table(const LoadedSweep& s) {
  std::vector<Cracks> cracks = ended_cracks(s.cases, s.sweep.crack_time);
  common::write_whole_text(s.out / kTableFile, table_csv(s.cases, cracks, s.out));
  return cracks;
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

/// The table on the terminal and the figures, from sweep.csv.
void show_table(const LoadedSweep& s, const std::vector<Cracks>& cracks) {
  print_table(s.cases, cracks, s.sweep.crack_time);
  fmt::print("\nwrote {}\n", (s.out / kTableFile).string());
  std::fflush(stdout);  // before the plotting script prints to the same terminal
  draw_figures({"sweep", (s.out / kTableFile).string(), "--out", (s.out / "figures").string()});
}

/// A shell word: single-quoted, each single quote ended, escaped and reopened.
std::string shell_word(const std::string& text) {
  std::string quoted = "'";
  for (const char c : text) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

std::string shell_array(const std::vector<std::string>& words) {
  std::string text = "(";
  for (const std::string& w : words) text += (text.size() > 1 ? " " : "") + shell_word(w);
  return text + ")";
}

/// The Slurm job array of the cases to run, longest expected first: array task K runs the K-th
/// as `ddafrac run` into its run directory (logged to its run.log), from its checkpoint if it has
/// one (a task run again, or requeued, continues), with the sweep's threads per case.
std::string slurm_script(const LoadedSweep& s, const CaseRunSettings& settings, const std::string& command) {
  const std::vector<std::size_t> order = dispatch_order(s.cases);
  const fs::path out = fs::absolute(s.out);
  std::string text = fmt::format(
      "#!/bin/bash\n"
      "# The sweep \"{0}\" as a Slurm job array, one case per array task, longest expected first.\n"
      "# Written by: {1}\n"
      "# Submit:     sbatch {2}\n"
      "# Tabulate what has finished, at any time: ddafrac sweep --collect {3}\n"
      "# A task run again (sbatch --array=K {2}) continues its case from its checkpoint.\n"
      "#SBATCH --job-name={0}\n"
      "#SBATCH --array=0-{4}\n"
      "#SBATCH --ntasks=1\n"
      "#SBATCH --cpus-per-task={5}\n"
      "#SBATCH --output={6}/slurm-%A_%a.out\n"
      "set -eu\n"
      "export OMP_NUM_THREADS={5}\n"
      "case \"${{SLURM_ARRAY_TASK_ID:?submit with sbatch, or set SLURM_ARRAY_TASK_ID to a task number}}\" in\n",
      s.sweep.name, command, shell_word((out / kSlurmScriptFile).string()), shell_word(out.string()), order.size() - 1,
      settings.threads, out.string());  // #SBATCH lines are read by Slurm, not a shell: no quotes
  for (std::size_t task = 0; task < order.size(); ++task) {
    CaseRun c = s.cases[order[task]];
    c.run_dir = out / c.scene.name;
    c.scene_file = fs::absolute(c.scene_file);  // a task starts in the folder it was submitted from
    c.start = Start::Fresh;
    const std::vector<std::string> fresh = run_arguments(c, settings);
    c.start = Start::FromCheckpoint;
    text += fmt::format("  # {}: about {:.3g} block-steps\n  {}) dir={} fresh={} resume={} ;;\n", c.scene.name,
                        expected_cost(c.scene), task, shell_word(c.run_dir.string()), shell_array(fresh),
                        shell_array(run_arguments(c, settings)));
  }
  text += fmt::format(
      "  *) echo \"no case for array task $SLURM_ARRAY_TASK_ID (the tasks are 0-{0})\" >&2; exit 2 ;;\n"
      "esac\n"
      "mkdir -p \"$dir\"\n"
      "rm -f \"$dir/{1}\"\n"
      "status=0\n"
      "if [ -e \"$dir/{2}\" ]; then \"${{resume[@]}}\" >> \"$dir/run.log\" 2>&1 || status=$?\n"
      "else \"${{fresh[@]}}\" > \"$dir/run.log\" 2>&1 || status=$?; fi\n"
      "echo \"$status\" > \"$dir/{1}\"  # for --collect: a run that failed before its summary.json\n"
      "exit \"$status\"\n",
      order.size() - 1, kExitStatusFile, dda::kCheckpointFile);
  return text;
}

void emit_slurm(LoadedSweep& s, const SweepArguments& args) {
  if (args.resume)
    for (CaseRun& c : s.cases) decide_start(c);
  const std::size_t to_run = dispatch_order(s.cases).size();
  if (to_run == 0) {
    fmt::print("sweep {}: every case has finished; no job array written\n", s.sweep.name);
    return;
  }
  fs::create_directories(s.out);
  write_record(s);
  const CaseRunSettings settings{s.sweep.threads, 1, args.checkpoint_every, s.overrides, {}, nullptr};
  std::string command = fmt::format("ddafrac sweep {} --out {}", args.sweep_file, s.out.string());
  for (const std::string& o : s.command_overrides) command += " --set " + o;
  command += args.resume ? " --emit-slurm --resume" : " --emit-slurm";
  const fs::path script = s.out / kSlurmScriptFile;
  common::write_whole_text(script, slurm_script(s, settings, command));
  fs::permissions(script, fs::perms::owner_exec | fs::perms::group_exec, fs::perm_options::add);
  fmt::print(
      "sweep {}: {} case(s) as a Slurm job array of {} task(s), {} thread(s) each\nwrote {}\n"
      "submit it with: sbatch {}\ntabulate what has finished with: ddafrac sweep --collect {}\n",
      s.sweep.name, to_run, to_run, s.sweep.threads, script.string(), script.string(), s.out.string());
}

void collect(const SweepArguments& args) {
  LoadedSweep s = load_recorded(args.collect);
  for (CaseRun& c : s.cases) decide_start(c);  // a completed case's exit status and wall time
  for (CaseRun& c : s.cases) {
    if (c.start == Start::Finished) continue;
    c.wall_seconds = summary_wall(read_summary(c.run_dir)).value_or(0.0);
    // A task whose run failed, perhaps before writing its summary (a scene that cannot be meshed);
    // one stopped (Slurm's time limit, a signal) is unfinished: a resume continues it.
    const int status = std::atoi(file_text(c.run_dir / kExitStatusFile).value_or("0").c_str());
    if (status != 0 && case_state(c) != "unfinished") c.exit_code = status;
  }
  std::map<std::string, int> count_of;
  for (const CaseRun& c : s.cases) ++count_of[case_state(c)];
  std::string counts;
  for (const auto& [state, count] : count_of)
    counts += fmt::format("{}{} {}", counts.empty() ? "" : ", ", count, state);
  fmt::print("sweep {} in {}: {} cases: {}\n", s.sweep.name, s.out.string(), s.cases.size(), counts);
  show_table(s, write_table(s));
}

void run_sweep(const SweepArguments& args) {
  if (!args.collect.empty()) return collect(args);
  const CaseRanks ranks;
  LoadedSweep s = load(args.sweep_file, args.overrides, args.out);
  if (args.emit_slurm) {
    if (ranks.is_root()) emit_slurm(s, args);
    return;
  }

  const int parallel = args.parallel > 0      ? args.parallel
                       : s.sweep.parallel > 0 ? s.sweep.parallel
                                              : std::max(1, ranks.cores_for_runs() / s.sweep.threads);
  if (ranks.is_root()) {
    fmt::print("sweep {}: {} cases, {} at a time{}, {} thread(s) each, into {}\n", s.sweep.name, s.cases.size(),
               parallel, ranks.size() > 1 ? fmt::format(" on each of {} ranks", ranks.size()) : std::string(),
               s.sweep.threads, s.out.string());
    fs::create_directories(s.out);
    write_record(s);
  }
  if (args.resume)
    for (CaseRun& c : s.cases) decide_start(c);
  // sweep.csv after every case: a stopped sweep leaves the table of the cases ended so far.
  run_cases(s.cases, {s.sweep.threads, parallel, args.checkpoint_every, s.overrides, [&] { write_table(s); }, &ranks});
  if (!ranks.is_root()) return;

  show_table(s, write_table(s));
  const auto failed = std::count_if(s.cases.begin(), s.cases.end(), [](const CaseRun& c) { return c.exit_code != 0; });
  if (failed > 0) throw CommandFailed(fmt::format("{} of {} cases failed (see their run.log)", failed, s.cases.size()));
}

}  // namespace

void register_sweep_command(CLI::App& app) {
  auto args = std::make_shared<SweepArguments>();
  CLI::App* command = app.add_subcommand("sweep", "run a set of cases (a sweep file) and tabulate their cracks");
  auto* sweep_file =
      command->add_option("sweep", args->sweep_file, "sweep file (TOML), e.g. scenes/impact/cases.sweep.toml");
  command->add_option("--out", args->out, "output directory (default runs/<sweep name>)");
  command
      ->add_option("--parallel", args->parallel,
                   "runs at once (default: cores / threads per run); under mpirun or srun, per rank")
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
  command->add_flag("--emit-slurm", args->emit_slurm,
                    "write the cases as a Slurm job array (<out>/sweep.slurm, one case per array task; with --resume "
                    "only those not finished) instead of running them");
  command
      ->add_option("--collect", args->collect,
                   "tabulate the cases of a sweep's output directory as they stand (sweep.csv, figures); runs nothing")
      ->type_name("DIR")
      ->excludes(sweep_file);
  command->callback([args, sweep_file] {
    if (args->collect.empty() && sweep_file->count() == 0)
      throw CommandFailed("sweep: a sweep file is required (or --collect DIR)",
                          static_cast<int>(CLI::ExitCodes::RequiredError));
    run_sweep(*args);
  });
}

}  // namespace ddafrac::app
