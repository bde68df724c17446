// `ddafrac study source [--out DIR] [--resume] [--status] [--set key=value ...] [--parallel N]
// [--cases name,...]`: the source study as one resumable command. Runs the flattened discs, the
// pre-cracked discs and the 15 impact cases, each as its own `ddafrac run` process (the sweep's
// machinery, case_runs.hpp), then writes study.md, study.csv and the series' figures.
// The study keeps study.json in DIR (its --set values and, while it runs, its process id), so
// that --status and --resume know how it was started.

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <signal.h>
#include <unistd.h>
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "case_ranks.hpp"
#include "case_runs.hpp"
#include "commands.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/dda/checkpoint.hpp"
#include "figures.hpp"
#include "option_checks.hpp"
#include "study_source_report.hpp"

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

/// The study's cases by series, as scene files under scenes/ (their end times are the study's:
/// 2 ms for the discs, past the peak and the split; 1800 µs for the impacts, 3000 µs for the
/// fastest, case 15).
struct Series {
  const char* name;
  std::vector<const char*> scenes;
};
const Series kSeries[] = {
    {"flattened", {"brazilian/flattened_2045.toml", "brazilian/flattened_4107.toml", "brazilian/flattened_6081.toml"}},
    {"precracked",
     {"brazilian/precracked_30.toml", "brazilian/precracked_45.toml", "brazilian/precracked_60.toml",
      "brazilian/precracked_75.toml"}},
    {"impact-theta",
     {"impact/case01.toml", "impact/case02.toml", "impact/case03.toml", "impact/case04.toml", "impact/case05.toml",
      "impact/case06.toml", "impact/case07.toml"}},
    {"impact-gamma", {"impact/case08.toml", "impact/case09.toml", "impact/case10.toml"}},
    {"impact-v0",
     {"impact/case11.toml", "impact/case12.toml", "impact/case13.toml", "impact/case14.toml", "impact/case15.toml"}},
};

constexpr const char* kStudyFile = "study.json";  // --set values and the running study's pid
constexpr int kThreadsPerRun = 1;                 // runs go side by side on the cores

struct SourceArguments {
  std::string out = "study-source";
  bool resume = false;
  bool status = false;
  std::vector<std::string> overrides;
  int parallel = 0;
  std::vector<std::string> cases;  // scene names; empty: all
  std::optional<double> checkpoint_every;
};

/// Is the process alive (a study running in the directory)?
bool alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

json read_study_file(const fs::path& out) {
  const auto text = file_text(out / kStudyFile);
  return text ? json::parse(*text, nullptr, false) : json();
}

void write_study_file(const fs::path& out, const std::vector<std::string>& overrides, long pid) {
  common::write_whole_text(out / kStudyFile, json{{"set", overrides}, {"pid", pid}}.dump(2) + "\n");
}

/// The --set values: those given, or else those the study in `out` was started with.
std::vector<std::string> study_overrides(const SourceArguments& args, const json& study) {
  if (!args.overrides.empty() || !study.is_object() || !study.contains("set")) return args.overrides;
  return study["set"].get<std::vector<std::string>>();
}

std::vector<SourceCase> load_study(const SourceArguments& args, const std::vector<std::string>& overrides,
                                   const fs::path& out) {
  const fs::path scenes = fs::path(DDAFRAC_SOURCE_DIR) / "scenes";
  std::vector<fs::path> files;
  std::vector<std::string> series;
  for (const Series& s : kSeries)
    for (const char* scene : s.scenes) {
      files.push_back(scenes / scene);
      series.emplace_back(s.name);
    }
  std::vector<CaseRun> runs = load_case_runs(files, overrides, out, "the study's cases");
  std::vector<SourceCase> all;
  for (std::size_t k = 0; k < runs.size(); ++k) all.push_back({series[k], std::move(runs[k])});
  if (args.cases.empty()) return all;
  std::vector<SourceCase> chosen;
  for (const std::string& name : args.cases) {
    const auto it = std::find_if(all.begin(), all.end(), [&](const SourceCase& c) { return c.run.scene.name == name; });
    if (it == all.end()) {
      std::string names;
      for (const SourceCase& c : all) names += (names.empty() ? "" : ", ") + c.run.scene.name;
      throw CommandFailed(fmt::format("study source: --cases: no case named '{}'; the cases are: {}", name, names));
    }
    chosen.push_back(*it);
  }
  return chosen;
}

/// One line of --status: done, running, failed or to do, from the case's run directory.
std::string status_line(const SourceCase& source, bool study_running) {
  CaseRun c = source.run;
  const json s = read_summary(c.run_dir);
  decide_start(c);
  const auto reason = !s.is_discarded() && s.contains("exit") ? s["exit"].value("reason", "") : std::string();
  const double wall = summary_wall(s).value_or(0.0);
  const double t = !s.is_discarded() ? s.value("simulated_time", 0.0) : 0.0;
  const double end = c.scene.analysis.end_time;
  std::string state;
  if (c.start == Start::Finished) {
    state = "done";
  } else if (reason.empty()) {
    state = "to do";
  } else if (reason == "running" && study_running) {
    state = "running";
  } else if (reason == "numerical_trouble" || reason == "write_failed") {
    state = fmt::format("failed ({})", reason);
  } else if (c.start == Start::FromCheckpoint) {
    state = "to do (continues from its checkpoint)";
  } else {
    state = fmt::format("to do (from t = 0: {})",
                        reason == "completed" ? "its scene changed since" : "stopped with no checkpoint");
  }
  constexpr double kMicroseconds = 1e6;
  return fmt::format("{:<18} {:<14} {:>7.0f} / {:<7.0f} {:>9.1f}  {}\n", c.scene.name, source.series, t * kMicroseconds,
                     end * kMicroseconds, wall, state);
}

void print_status(const SourceArguments& args) {
  const fs::path out(args.out);
  if (!fs::exists(out / kStudyFile))
    throw CommandFailed(fmt::format("study source --status: {} holds no study (no {})", out.string(), kStudyFile));
  const json study = read_study_file(out);
  const long pid = study.is_object() ? study.value("pid", 0L) : 0L;
  const bool running = alive(pid);
  const std::vector<SourceCase> cases = load_study(args, study_overrides(args, study), out);
  fmt::print("study source in {}: {}\n", out.string(),
             running ? fmt::format("running (process {})", pid) : std::string("not running"));
  fmt::print("{:<18} {:<14} {:>17} {:>9}  {}\n", "case", "series", "t / end (µs)", "wall (s)", "state");
  for (const SourceCase& c : cases) fmt::print("{}", status_line(c, running));
}

/// The figures the plotting script draws for the study (names relative to the study directory).
std::vector<std::string> figure_names(const fs::path& out) {
  std::vector<std::string> names;
  const fs::path figures = out / "figures";
  if (!fs::exists(figures)) return names;
  for (const auto& entry : fs::directory_iterator(figures))
    if (entry.path().extension() == ".png" && entry.path().filename().string().front() != '.')
      names.push_back(fs::relative(entry.path(), out).string());
  std::sort(names.begin(), names.end());
  return names;
}

void run_study(const SourceArguments& args) {
  const CaseRanks ranks;  // under mpirun or srun, the cases are spread over the ranks
  const fs::path out(args.out);
  const json previous = read_study_file(out);
  if (ranks.is_root() && previous.is_object() && alive(previous.value("pid", 0L)) &&
      previous.value("pid", 0L) != ::getpid())
    throw CommandFailed(fmt::format("study source: a study is running in {} (process {}); see --status", out.string(),
                                    previous.value("pid", 0L)));
  const std::vector<std::string> overrides = args.resume ? study_overrides(args, previous) : args.overrides;
  std::vector<SourceCase> cases = load_study(args, overrides, out);

  const int parallel = args.parallel > 0 ? args.parallel : std::max(1, ranks.cores_for_runs() / kThreadsPerRun);
  if (ranks.is_root()) {
    fmt::print("study source: {} cases, {} at a time{}, {} thread each, into {}{}\n", cases.size(), parallel,
               ranks.size() > 1 ? fmt::format(" on each of {} ranks", ranks.size()) : std::string(), kThreadsPerRun,
               out.string(),
               overrides.empty() ? std::string() : fmt::format(" (--set {})", fmt::join(overrides, " --set ")));
    fs::create_directories(out);
    write_study_file(out, overrides, ::getpid());
  }
  std::vector<CaseRun> runs;
  for (SourceCase& c : cases) {
    if (args.resume) decide_start(c.run);
    runs.push_back(c.run);
  }
  const auto write_tables = [&](const std::vector<std::string>& figures) {
    common::write_whole_text(out / "study.csv", study_csv(cases, out));
    common::write_whole_text(out / "study.md", study_markdown(cases, overrides, figures));
  };
  // study.md after every case: an interrupted study leaves the table of the cases done so far.
  run_cases(runs, {kThreadsPerRun, parallel, args.checkpoint_every, overrides, [&] { write_tables({}); }, &ranks});
  if (!ranks.is_root()) return;
  for (std::size_t k = 0; k < cases.size(); ++k) cases[k].run = runs[k];
  write_tables({});
  std::fflush(stdout);  // before the plotting script prints to the same terminal
  draw_figures({"study-source", out.string()});
  write_tables(figure_names(out));
  write_study_file(out, overrides, 0);
  fmt::print("wrote {}\n", (out / "study.md").string());

  const auto failed = std::count_if(runs.begin(), runs.end(), [](const CaseRun& c) { return c.exit_code != 0; });
  if (failed > 0) throw CommandFailed(fmt::format("{} of {} cases failed (see their run.log)", failed, runs.size()));
}

}  // namespace

void register_study_source(CLI::App& study) {
  auto args = std::make_shared<SourceArguments>();
  CLI::App* command = study.add_subcommand(
      "source", "the source study: flattened and pre-cracked discs, impact cases 1-15, as one resumable command");
  command->add_option("--out", args->out, "study directory")->capture_default_str();
  auto* resume = command->add_flag("--resume", args->resume,
                                   "keep the cases that finished with the scene they have now, continue stopped ones "
                                   "from their checkpoints, run the rest (with the --set values the study began with)");
  auto* status = command->add_flag(
      "--status", args->status, "list the cases as done / running / failed / to do with their run times; run nothing");
  status->excludes(resume);
  command
      ->add_option(
          "--set", args->overrides,
          "override a value of every case, e.g. --set mesh.blocks=700 (a reduced study: every scene meshes at 700)")
      ->type_name("KEY=VALUE");
  command->add_option("--parallel", args->parallel, "runs at once (default: the cores)")
      ->check(whole_number(1, kMaxParallelRuns))
      ->excludes(status);
  command->add_option("--cases", args->cases, "only these cases (comma-separated scene names)")->delimiter(',');
  command
      ->add_option("--checkpoint-every", args->checkpoint_every,
                   "wall seconds between the checkpoints of each run (default: that of ddafrac run)")
      ->check(non_negative_number())
      ->excludes(status);
  command->callback([args] { args->status ? print_status(*args) : run_study(*args); });
}

}  // namespace ddafrac::app
