#pragma once
// What the studies that run many cases share (`ddafrac study source`, `study sensitivity`):
// their options, the study directory's study.json (the --set values it was started with and,
// while it runs, its process id), --status, and the run itself (each case a `ddafrac run`
// process through case_runs.hpp, the tables rewritten after every case, then the figures).

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "case_runs.hpp"

namespace ddafrac::app {

/// A case of a study: its run and the series (or family) it belongs to.
struct StudyCase {
  std::string series;  // e.g. "impact-theta"
  CaseRun run;
  /// The earlier case whose scene this one repeats under another name (the source study's cases
  /// 8 and 12 are case 4): it runs once, as that case, and run.run_dir is that case's. Empty:
  /// a case with its own run.
  std::string repeat_of;
};

struct StudyArguments {
  std::string out;
  bool resume = false;
  bool status = false;
  bool report = false;  // write the tables and figures of the cases finished so far, run nothing
  std::vector<std::string> overrides;
  int parallel = 0;
  std::vector<std::string> cases;  // scene names; empty: all
  std::optional<double> checkpoint_every;
};

/// A study as the shared code sees it: its command name ("study source"), how to load its
/// cases with given --set values, its study.md and which figures to draw. The shared run writes
/// study.md and study.csv (what the figures read) after every case and at the end.
struct StudyKind {
  std::string command;          // e.g. "study source", for messages
  std::string figures_command;  // the plotting script's subcommand, e.g. "study-source"
  std::function<std::vector<StudyCase>(const std::vector<std::string>& overrides)> load;
  /// study.md of the cases with the --set values and the figures drawn so far (relative to the
  /// study directory).
  std::function<std::string(const std::vector<StudyCase>& cases, const std::vector<std::string>& overrides,
                            const std::vector<std::string>& figures)>
      markdown;
  /// The kind's own options that choose its cases besides --set (sensitivity's --family and
  /// --blocks), as text: written to study.json, so that a later --status, --report or --resume
  /// given without them reads them back (stored_study_options) and lists the same cases.
  std::map<std::string, std::string> options;
};

/// study.csv: case, series, run_dir (relative to `out`), state of its summary.json.
std::string study_csv(const std::vector<StudyCase>& cases, const std::filesystem::path& out);

/// Adds --out (default `default_out`), --resume, --status, --set (its help: `set_help`),
/// --parallel, --cases and --checkpoint-every, and a callback that prints the status or runs
/// the study. `args` must outlive the command (the callback refers to it).
void add_study_options(CLI::App& command, StudyArguments& args, const std::string& default_out,
                       const std::string& set_help, std::function<StudyKind()> kind);

/// The study file of the study in `out` (study.json: its --set values, options and pid).
std::filesystem::path study_file(const std::filesystem::path& out);

/// The options (StudyKind::options) the study in `out` was started with; empty if there is no
/// study there or it recorded none.
std::map<std::string, std::string> stored_study_options(const std::filesystem::path& out);

/// Marks every case whose scene repeats an earlier case's under another name (equal
/// Scene::unnamed_text): its repeat_of and run directory become the earlier case's.
void mark_repeats(std::vector<StudyCase>& cases);

/// Only the cases named in `names` (all when empty), in that order; throws CommandFailed
/// listing the cases when a name is unknown.
std::vector<StudyCase> choose_cases(std::vector<StudyCase> all, const std::vector<std::string>& names,
                                    const std::string& command);

/// The figures drawn into `out`/figures, relative to `out`, sorted.
std::vector<std::string> figure_names(const std::filesystem::path& out);

}  // namespace ddafrac::app
