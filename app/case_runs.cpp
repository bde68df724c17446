#include "case_runs.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

#include "case_ranks.hpp"
#include "commands.hpp"
#include "ddafrac/dda/checkpoint.hpp"
#include "ddafrac/dda/run.hpp"
#include "ddafrac/scene/parse.hpp"
#include "subprocess.hpp"

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

/// Each case runs in the folder of its scene name: two cases of one name would overwrite each
/// other's run, so they are refused before anything runs.
void refuse_shared_names(const std::vector<CaseRun>& cases) {
  std::map<std::string, std::vector<std::string>> files_of;
  for (const CaseRun& c : cases) files_of[c.scene.name].push_back(c.scene_file.string());
  std::string problems;
  for (const auto& [name, files] : files_of)
    if (files.size() > 1) problems += fmt::format("\n  \"{}\": {}", name, fmt::join(files, ", "));
  if (!problems.empty())
    throw CommandFailed(
        "cases share a scene name, so their runs would overwrite each other (nothing was run; give "
        "each a name = \"...\"):" +
        problems);
}

}  // namespace

std::vector<std::string> run_arguments(const CaseRun& c, const CaseRunSettings& settings) {
  std::vector<std::string> argv{own_executable().string(), "run", "--threads", std::to_string(settings.threads)};
  if (settings.checkpoint_every) {
    argv.push_back("--checkpoint-every");
    argv.push_back(fmt::format("{:.17g}", *settings.checkpoint_every));
  }
  if (c.start == Start::FromCheckpoint) {
    argv.push_back("--resume");
    argv.push_back(c.run_dir.string());
    return argv;
  }
  for (const std::string& item : {c.scene_file.string(), std::string("--out"), c.run_dir.string()})
    argv.push_back(item);
  for (const std::string& o : settings.overrides) {
    argv.push_back("--set");
    argv.push_back(o);
  }
  return argv;
}

std::string csv_field(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (const char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + '"';
}

std::vector<CaseRun> load_case_runs(const std::vector<fs::path>& scene_files, const std::vector<std::string>& overrides,
                                    const fs::path& out, const std::string& what) {
  std::vector<CaseRun> cases;
  // The same problem in many cases (a bad --set value, a shared base scene) is said once.
  std::vector<std::pair<std::string, std::vector<std::string>>> problems;  // message, files
  for (const fs::path& file : scene_files) {
    try {
      CaseRun c;
      c.scene_file = file;
      c.scene = scene::load_scene(file, overrides);
      c.run_dir = out / c.scene.name;
      cases.push_back(std::move(c));
    } catch (const scene::SceneError& e) {
      const auto same =
          std::find_if(problems.begin(), problems.end(), [&](const auto& p) { return p.first == e.what(); });
      if (same == problems.end())
        problems.push_back({e.what(), {file.string()}});
      else
        same->second.push_back(file.string());
    }
  }
  if (!problems.empty()) {
    std::string text;
    for (const auto& [message, files] : problems) text += fmt::format("\n{}: {}", fmt::join(files, ", "), message);
    throw CommandFailed(what + " have problems (nothing was run):" + text);
  }
  refuse_shared_names(cases);
  return cases;
}

std::optional<std::string> file_text(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return std::nullopt;
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

nlohmann::json read_summary(const fs::path& run_dir) {
  std::ifstream in(run_dir / "summary.json");
  return nlohmann::json::parse(in, nullptr, false);
}

std::optional<double> summary_wall(const nlohmann::json& summary) {
  if (summary.is_discarded() || !summary.contains("wall_time")) return std::nullopt;
  return summary["wall_time"].value("total", 0.0);
}

/// A case whose run completed with the scene it has now is finished (its wall time is the
/// run's); one with a checkpoint of that scene continues from it; any other (never started,
/// failed, or its scene changed since) starts again from t = 0.
void decide_start(CaseRun& c) {
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

double expected_cost(const scene::Scene& s) {
  return static_cast<double>(s.mesh.target_blocks) * s.analysis.end_time / s.analysis.dt_max;
}

std::vector<std::size_t> dispatch_order(const std::vector<CaseRun>& cases) {
  std::vector<std::size_t> order;
  for (std::size_t k = 0; k < cases.size(); ++k)
    if (cases[k].start != Start::Finished) order.push_back(k);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return expected_cost(cases[a].scene) > expected_cost(cases[b].scene);
  });
  return order;
}

pid_t start_case(const CaseRun& c, const CaseRunSettings& settings, const std::string& where) {
  fs::create_directories(c.run_dir);
  const fs::path log = c.run_dir / "run.log";
  // A resumed run's log goes on after the stopped one's.
  if (c.start == Start::Fresh) fs::remove(log);
  // The run is a process of its own, not a call in this one: a run that crashes or is killed
  // loses only its case, and under MPI the rank goes on. Spawning costs milliseconds against a
  // case's seconds to hours. The child gets no MPI launcher variables, so that it never takes
  // itself for this rank.
  // It stops (resumably) if this process ends first, so a killed sweep leaves no run behind.
  std::vector<std::string> argv = run_arguments(c, settings);
  argv.insert(argv.end(), {"--stop-with-parent", std::to_string(::getpid())});
  const pid_t pid = spawn_process(argv, log, environment_outside_mpi(), kThisExecutable);
  fmt::print("{} {} ({}){}\n", c.start == Start::FromCheckpoint ? "resumed " : "started ", c.scene.name,
             c.scene_file.string(), where);
  std::fflush(stdout);
  return pid;
}

void record_end(CaseRun& c, int exit_code, double measured_seconds) {
  c.exit_code = exit_code;
  c.wall_seconds = measured_seconds;
  // A resumed case took the time of all its parts.
  if (c.start == Start::FromCheckpoint)
    c.wall_seconds = summary_wall(read_summary(c.run_dir)).value_or(measured_seconds);
}

void print_end(const CaseRun& c, std::size_t done, std::size_t total, const std::string& where) {
  fmt::print(
      "[{}/{}] {} {} in {:.1f} s{}{}\n", done, total, c.scene.name, c.exit_code == 0 ? "finished" : "FAILED",
      c.wall_seconds, where,
      c.exit_code == 0 ? "" : fmt::format(" (exit status {}; see {})", c.exit_code, (c.run_dir / "run.log").string()));
  std::fflush(stdout);
}

void run_cases(std::vector<CaseRun>& cases, const CaseRunSettings& settings) {
  std::size_t done = 0;
  const bool prints = !settings.ranks || settings.ranks->is_root();
  for (const CaseRun& c : cases) {
    if (c.start != Start::Finished) continue;
    ++done;
    if (prints) fmt::print("[{}/{}] {} finished before (kept)\n", done, cases.size(), c.scene.name);
  }
  if (settings.ranks && settings.ranks->size() > 1) return run_cases_over_ranks(cases, settings, *settings.ranks);

  const std::vector<std::size_t> order = dispatch_order(cases);
  std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
  std::size_t next = 0;
  while (done < cases.size()) {
    while (next < order.size() && static_cast<int>(running.size()) < settings.parallel) {
      running[start_case(cases[order[next]], settings, "")] = {order[next], Clock::now()};
      ++next;
    }
    const Finished finished = wait_for_any_child();
    const auto it = running.find(finished.pid);
    if (it == running.end()) continue;
    CaseRun& c = cases[it->second.first];
    record_end(c, finished.exit_code, std::chrono::duration<double>(Clock::now() - it->second.second).count());
    running.erase(it);
    print_end(c, ++done, cases.size(), "");
    if (settings.after_each) settings.after_each();
  }
}

}  // namespace ddafrac::app
