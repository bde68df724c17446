#include "study_runs.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "case_ranks.hpp"
#include "commands.hpp"
#include "ddafrac/common/stopwatch.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "figures.hpp"
#include "option_checks.hpp"

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kStudyFile = "study.json";  // --set values, the kind's options and the running study's pid

/// Runs that go at once: --parallel (default the cores), but no more than there are to run.
int runs_at_once(int parallel, std::size_t cases_to_run) {
  return std::max(1, std::min(parallel, static_cast<int>(cases_to_run)));
}

/// Threads of each run: the cores shared among the runs that go at once, so that the study's own
/// processes neither oversubscribe the cores nor leave one idle (one case left to run, or
/// --parallel 1, on two cores gets two threads).
int threads_per_run(int cores, int at_once) { return std::max(1, cores / at_once); }

/// Is the process alive (a study running in the directory)?
bool alive(long pid) { return pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno == EPERM); }

json read_study_file(const fs::path& out) {
  const auto text = file_text(out / kStudyFile);
  return text ? json::parse(*text, nullptr, false) : json();
}

void write_study_file(const fs::path& out, const StudyKind& kind, const std::vector<std::string>& overrides, long pid) {
  common::write_whole_text(out / kStudyFile,
                           json{{"set", overrides}, {"options", kind.options}, {"pid", pid}}.dump(2) + "\n");
}

/// The --set values: those given, or else those the study in `out` was started with.
std::vector<std::string> study_overrides(const StudyArguments& args, const json& study) {
  if (!args.overrides.empty() || !study.is_object() || !study.contains("set")) return args.overrides;
  return study["set"].get<std::vector<std::string>>();
}

/// The kind's cases with the --set values, repeats marked (mark_repeats).
std::vector<StudyCase> load_cases(const StudyKind& kind, const std::vector<std::string>& overrides) {
  std::vector<StudyCase> cases = kind.load(overrides);
  mark_repeats(cases);
  return cases;
}

/// The case whose run `c` shows: `c` itself, or the case of `all` it repeats.
const StudyCase& shown_case(const StudyCase& c, const std::vector<StudyCase>& all) {
  if (c.repeat_of.empty()) return c;
  return *std::find_if(all.begin(), all.end(), [&](const StudyCase& o) { return o.run.scene.name == c.repeat_of; });
}

/// The chosen cases with each repeat replaced by the case it repeats (once): what runs. Says so
/// for each repeat, so that a user who chose case 8 sees why case 4 runs.
std::vector<StudyCase> cases_to_run(const std::vector<StudyCase>& chosen, const std::vector<StudyCase>& all) {
  std::vector<StudyCase> runs;
  for (const StudyCase& c : chosen) {
    const StudyCase& shown = shown_case(c, all);
    if (&shown != &c)
      fmt::print("{} repeats {}'s scene under another name: it runs once, as {}\n", c.run.scene.name,
                 shown.run.scene.name, shown.run.scene.name);
    if (std::none_of(runs.begin(), runs.end(),
                     [&](const StudyCase& r) { return r.run.scene.name == shown.run.scene.name; }))
      runs.push_back(shown);
  }
  return runs;
}

/// One line of --status: done, running, failed or to do, from the case's run directory.
std::string status_line(const StudyCase& study_case, const std::vector<StudyCase>& all, bool study_running,
                        std::size_t name_width, std::size_t series_width) {
  CaseRun c = shown_case(study_case, all).run;
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
    // At the pace of its run so far: a guess, as a run slows down where cracks multiply.
    if (t > 0.0 && wall > 0.0 && end > t)
      state += fmt::format(", about {} left", common::duration_text(wall * (end - t) / t));
  } else if (reason == "numerical_trouble" || reason == "write_failed") {
    state = fmt::format("failed ({})", reason);
  } else if (c.start == Start::FromCheckpoint) {
    state = "to do (continues from its checkpoint)";
  } else {
    state = fmt::format("to do (from t = 0: {})",
                        reason == "completed" ? "its scene changed since" : "stopped with no checkpoint");
  }
  constexpr double kMicroseconds = 1e6;
  if (!study_case.repeat_of.empty()) state += fmt::format(" ({}'s run)", study_case.repeat_of);
  return fmt::format("{:<{}} {:<{}} {:>7.0f} / {:<7.0f} {:>9.1f}  {}\n", study_case.run.scene.name, name_width,
                     study_case.series, series_width, t * kMicroseconds, end * kMicroseconds, wall, state);
}

/// The study file of the study in `out`; throws CommandFailed naming the option if there is none.
json existing_study(const StudyKind& kind, const fs::path& out, const char* option) {
  if (!fs::exists(out / kStudyFile))
    throw CommandFailed(
        fmt::format("{} {}: {} holds no study (no {})", kind.command, option, out.string(), kStudyFile));
  return read_study_file(out);
}

void print_status(const StudyKind& kind, const StudyArguments& args) {
  const fs::path out(args.out);
  const json study = existing_study(kind, out, "--status");
  const long pid = study.is_object() ? study.value("pid", 0L) : 0L;
  const bool running = alive(pid);
  const std::vector<StudyCase> all = load_cases(kind, study_overrides(args, study));
  const std::vector<StudyCase> cases = choose_cases(all, args.cases, kind.command);
  fmt::print("{} in {}: {}\n", kind.command, out.string(),
             running ? fmt::format("running (process {})", pid) : std::string("not running"));
  constexpr std::size_t kNameWidth = 18, kSeriesWidth = 14;  // at least; wider for longer names
  std::size_t name_width = kNameWidth, series_width = kSeriesWidth;
  for (const StudyCase& c : cases) {
    name_width = std::max(name_width, c.run.scene.name.size());
    series_width = std::max(series_width, c.series.size());
  }
  fmt::print("{:<{}} {:<{}} {:>17} {:>9}  {}\n", "case", name_width, "series", series_width, "t / end (µs)", "wall (s)",
             "state");
  for (const StudyCase& c : cases) fmt::print("{}", status_line(c, all, running, name_width, series_width));
}

/// study.csv and study.md, each written whole.
void write_tables(const StudyKind& kind, const fs::path& out, const std::vector<StudyCase>& cases,
                  const std::vector<std::string>& overrides, const std::vector<std::string>& figures) {
  common::write_whole_text(out / "study.csv", study_csv(cases, out));
  common::write_whole_text(out / "study.md", kind.markdown(cases, overrides, figures));
}

/// study.md and study.csv with the series' figures, from what the cases' run directories hold.
void write_report(const StudyKind& kind, const fs::path& out, const std::vector<StudyCase>& cases,
                  const std::vector<std::string>& overrides) {
  write_tables(kind, out, cases, overrides, {});
  std::fflush(stdout);  // before the plotting script prints to the same terminal
  draw_figures({kind.figures_command, out.string()});
  write_tables(kind, out, cases, overrides, figure_names(out));
  fmt::print("wrote {}\n", (out / "study.md").string());
}

/// Every case of the study, those in `ran` as they ran (their exit status): the report of a
/// study describes the whole study, also when --cases ran only some of it.
std::vector<StudyCase> whole_study(std::vector<StudyCase> all, const std::vector<StudyCase>& ran) {
  for (StudyCase& c : all)
    for (const StudyCase& r : ran)
      if (r.run.scene.name == c.run.scene.name) c = r;
  return all;
}

/// --report: the report of the cases run so far (the rest marked not run), whether or not
/// the study is still running; runs nothing.
void report_study(const StudyKind& kind, const StudyArguments& args) {
  const fs::path out(args.out);
  const std::vector<std::string> overrides = study_overrides(args, existing_study(kind, out, "--report"));
  write_report(kind, out, load_cases(kind, overrides), overrides);
}

void run_study(const StudyKind& kind, const StudyArguments& args) {
  const CaseRanks ranks;  // under mpirun or srun, the cases are spread over the ranks
  const fs::path out(args.out);
  const json previous = read_study_file(out);
  if (ranks.is_root() && previous.is_object() && alive(previous.value("pid", 0L)) &&
      previous.value("pid", 0L) != ::getpid())
    throw CommandFailed(fmt::format("{}: a study is running in {} (process {}); see --status", kind.command,
                                    out.string(), previous.value("pid", 0L)));
  const std::vector<std::string> overrides = args.resume ? study_overrides(args, previous) : args.overrides;
  const std::vector<StudyCase> all = load_cases(kind, overrides);
  std::vector<StudyCase> cases = cases_to_run(choose_cases(all, args.cases, kind.command), all);

  std::vector<CaseRun> runs;
  for (StudyCase& c : cases) {
    if (args.resume) decide_start(c.run);
    runs.push_back(c.run);
  }
  const int cores = ranks.cores_for_runs();
  const std::size_t to_run = dispatch_order(runs).size();
  const int parallel = runs_at_once(args.parallel > 0 ? args.parallel : cores, to_run);
  const int threads = threads_per_run(cores, parallel);
  if (ranks.is_root()) {
    fmt::print("{}: {} case{} ({} to run), {} at a time{}, {} thread(s) each, into {}{}\n", kind.command,
               cases.size(), cases.size() == 1 ? "" : "s", to_run, parallel,
               ranks.size() > 1 ? fmt::format(" on each of {} ranks", ranks.size()) : std::string(), threads,
               out.string(),
               overrides.empty() ? std::string() : fmt::format(" (--set {})", fmt::join(overrides, " --set ")));
    fs::create_directories(out);
    write_study_file(out, kind, overrides, ::getpid());
  }
  // The tables after every case: an interrupted study leaves those of the cases done so far.
  run_cases(runs, {threads, parallel, args.checkpoint_every, overrides,
                   [&] { write_tables(kind, out, whole_study(all, cases), overrides, {}); }, &ranks});
  if (!ranks.is_root()) return;
  for (std::size_t k = 0; k < cases.size(); ++k) cases[k].run = runs[k];
  write_report(kind, out, whole_study(all, cases), overrides);
  write_study_file(out, kind, overrides, 0);

  const auto failed = std::count_if(runs.begin(), runs.end(), [](const CaseRun& c) { return c.exit_code != 0; });
  if (failed > 0) throw CommandFailed(fmt::format("{} of {} cases failed (see their run.log)", failed, runs.size()));
}

}  // namespace

std::string study_csv(const std::vector<StudyCase>& cases, const fs::path& out) {
  std::string csv = "case,series,run_dir,exit_reason\n";
  for (const StudyCase& c : cases) {
    const json s = read_summary(c.run.run_dir);
    const std::string reason = !s.is_discarded() && s.contains("exit") ? s["exit"].value("reason", "") : "";
    csv += fmt::format("{},{},{},{}\n", c.run.scene.name, c.series,
                       csv_field(fs::relative(c.run.run_dir, out).string()), reason);
  }
  return csv;
}

fs::path study_file(const fs::path& out) { return out / kStudyFile; }

std::map<std::string, std::string> stored_study_options(const fs::path& out) {
  const json study = read_study_file(out);
  std::map<std::string, std::string> options;
  if (!study.is_object() || !study.contains("options") || !study["options"].is_object()) return options;
  for (const auto& [key, value] : study["options"].items()) {
    if (!value.is_string())
      throw CommandFailed(
          fmt::format("{}: options.{} is not text; was the file edited?", study_file(out).string(), key));
    options[key] = value.get<std::string>();
  }
  return options;
}

void mark_repeats(std::vector<StudyCase>& cases) {
  for (auto c = cases.begin(); c != cases.end(); ++c) {
    const auto first = std::find_if(cases.begin(), c, [&](const StudyCase& o) {
      return o.repeat_of.empty() && !o.run.scene.unnamed_text.empty() &&
             o.run.scene.unnamed_text == c->run.scene.unnamed_text;
    });
    if (first == c) continue;
    c->repeat_of = first->run.scene.name;
    c->run.run_dir = first->run.run_dir;
  }
}

std::vector<StudyCase> choose_cases(std::vector<StudyCase> all, const std::vector<std::string>& names,
                                    const std::string& command) {
  if (names.empty()) return all;
  std::vector<StudyCase> chosen;
  for (const std::string& name : names) {
    const auto it = std::find_if(all.begin(), all.end(), [&](const StudyCase& c) { return c.run.scene.name == name; });
    if (it == all.end()) {
      std::string list;
      for (const StudyCase& c : all) list += (list.empty() ? "" : ", ") + c.run.scene.name;
      throw CommandFailed(fmt::format("{}: --cases: no case named '{}'; the cases are: {}", command, name, list));
    }
    chosen.push_back(*it);
  }
  return chosen;
}

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

void add_study_options(CLI::App& command, StudyArguments& args, const std::string& default_out,
                       const std::string& set_help, std::function<StudyKind()> kind) {
  args.out = default_out;
  command.add_option("--out", args.out, "study directory")->capture_default_str();
  auto* resume = command.add_flag(
      "--resume", args.resume,
      "keep the cases that finished with the scene they have now, continue stopped ones "
      "from their checkpoints, run the rest (with the --set values, and the options that choose the cases, "
      "the study began with)");
  auto* status = command.add_flag(
      "--status", args.status, "list the cases as done / running / failed / to do with their run times; run nothing");
  status->excludes(resume);
  auto* report = command.add_flag("--report", args.report,
                                  "write study.md, study.csv and the figures of the cases run so far (the rest "
                                  "marked not run), also while the study runs; run nothing");
  report->excludes(resume)->excludes(status);
  command.add_option("--set", args.overrides, set_help)->type_name("KEY=VALUE");
  command.add_option("--parallel", args.parallel, "runs at once (default: the cores)")
      ->check(whole_number(1, kMaxParallelRuns))
      ->excludes(status)
      ->excludes(report);
  command
      .add_option("--cases", args.cases,
                  "run (or list) only these cases (comma-separated scene names); the report still covers every case")
      ->delimiter(',')
      ->excludes(report);
  command
      .add_option("--checkpoint-every", args.checkpoint_every,
                  "wall seconds between the checkpoints of each run (default: that of ddafrac run)")
      ->check(non_negative_number())
      ->excludes(status)
      ->excludes(report);
  command.callback([&args, kind] {
    const StudyKind k = kind();
    if (args.status)
      print_status(k, args);
    else if (args.report)
      report_study(k, args);
    else
      run_study(k, args);
  });
}

}  // namespace ddafrac::app
