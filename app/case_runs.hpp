#pragma once
// Many cases, each run as its own `ddafrac run` process, several at once: what `ddafrac sweep`
// and `ddafrac study source` share. A case runs in <out>/<scene name>; with a resume, a case that
// completed with the scene it has now is kept, one with a checkpoint continues from it, and the
// rest run from t = 0. Under an MPI launcher the cases are spread over the ranks (case_ranks.hpp).

#include <nlohmann/json.hpp>

#include <sys/types.h>
#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ddafrac/scene/scene.hpp"

namespace ddafrac::app {

class CaseRanks;

/// How a case starts: from t = 0, from its checkpoint, or not at all (finished before).
enum class Start { Fresh, FromCheckpoint, Finished };

/// One case: its scene (validated before anything runs) and, once run, how it ended.
struct CaseRun {
  std::filesystem::path scene_file;
  scene::Scene scene;
  std::filesystem::path run_dir;
  Start start = Start::Fresh;
  int exit_code = -1;
  double wall_seconds = 0.0;  // of all the run's parts, a resumed run's included
};

/// Loads and validates every scene with `overrides` applied; throws CommandFailed listing every
/// problem (`what` names the set, e.g. "the sweep's cases") before anything runs, and when two
/// cases share a scene name (their runs would overwrite each other).
std::vector<CaseRun> load_case_runs(const std::vector<std::filesystem::path>& scene_files,
                                    const std::vector<std::string>& overrides, const std::filesystem::path& out,
                                    const std::string& what);

/// For a resume: Finished (with its wall time), FromCheckpoint or Fresh, from the run directory.
void decide_start(CaseRun& c);

struct CaseRunSettings {
  int threads = 1;                         // OpenMP threads of each run
  int parallel = 1;                        // runs at once
  std::optional<double> checkpoint_every;  // s, passed to every run (default: the run's own)
  std::vector<std::string> overrides;      // `--set` values of every run
  std::function<void()> after_each;        // called after each case ends (e.g. to rewrite a table)
  const CaseRanks* ranks = nullptr;        // the MPI ranks to spread the cases over; none: this process
};

/// What a case is expected to cost, in block-steps: blocks × (end time / largest time step). The
/// cases are handed out in falling order of it, so that the longest do not start last.
double expected_cost(const scene::Scene& s);

/// The indices of the cases to run (not Finished), longest expected first (file order among
/// equals).
std::vector<std::size_t> dispatch_order(const std::vector<CaseRun>& cases);

/// Runs the cases that are not Finished, longest expected first, `parallel` at a time (per rank
/// under MPI), each logged to its run.log, printing a line as each starts and ends; records exit
/// codes and wall times. Under MPI only rank 0 calls after_each, and only its `cases` end complete.
void run_cases(std::vector<CaseRun>& cases, const CaseRunSettings& settings);

/// The `ddafrac run` command line of a case: a fresh run into its run directory, or the resume
/// of its checkpoint.
std::vector<std::string> run_arguments(const CaseRun& c, const CaseRunSettings& settings);

/// Starts a case's `ddafrac run` (its run.log restarted unless it resumes) and prints the line
/// saying so, with `where` (the rank) appended.
pid_t start_case(const CaseRun& c, const CaseRunSettings& settings, const std::string& where);

/// Records how a case ended: its exit code and wall time (a resumed run's over all its parts).
void record_end(CaseRun& c, int exit_code, double measured_seconds);

/// Prints "[done/total] case finished in ... s", or FAILED with the exit status and the log.
void print_end(const CaseRun& c, std::size_t done, std::size_t total, const std::string& where);

/// A run's summary.json, or a discarded value if it cannot be read.
nlohmann::json read_summary(const std::filesystem::path& run_dir);

/// A run's wall time over all its parts (a resumed run's included), from its summary.json.
std::optional<double> summary_wall(const nlohmann::json& summary);

/// The text of a file, or nothing if it cannot be read.
std::optional<std::string> file_text(const std::filesystem::path& file);

/// A CSV field: quoted (quotes doubled) when it holds a comma, a quote or a line break.
std::string csv_field(const std::string& text);

}  // namespace ddafrac::app
