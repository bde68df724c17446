#include "case_runs.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>

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

}  // namespace

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

void run_cases(std::vector<CaseRun>& cases, const CaseRunSettings& settings) {
  std::map<pid_t, std::pair<std::size_t, Clock::time_point>> running;
  std::size_t next = 0, done = 0;
  while (done < cases.size()) {
    while (next < cases.size() && static_cast<int>(running.size()) < settings.parallel) {
      CaseRun& c = cases[next++];
      if (c.start == Start::Finished) {
        fmt::print("[{}/{}] {} finished before (kept)\n", ++done, cases.size(), c.scene.name);
        continue;
      }
      fs::create_directories(c.run_dir);
      const fs::path log = c.run_dir / "run.log";
      // A resumed run's log goes on after the stopped one's.
      if (c.start == Start::Fresh) fs::remove(log);
      running[spawn_process(run_arguments(c, settings), log)] = {next - 1, Clock::now()};
      fmt::print("{} {} ({})\n", c.start == Start::FromCheckpoint ? "resumed " : "started ", c.scene.name,
                 c.scene_file.string());
      std::fflush(stdout);
    }
    if (done == cases.size()) break;
    const Finished finished = wait_for_any_child();
    const auto it = running.find(finished.pid);
    if (it == running.end()) continue;
    CaseRun& c = cases[it->second.first];
    c.exit_code = finished.exit_code;
    c.wall_seconds = std::chrono::duration<double>(Clock::now() - it->second.second).count();
    running.erase(it);
    ++done;
    fmt::print("[{}/{}] {} {} in {:.1f} s{}\n", done, cases.size(), c.scene.name,
               c.exit_code == 0 ? "finished" : "FAILED", c.wall_seconds,
               c.exit_code == 0
                   ? ""
                   : fmt::format(" (exit status {}; see {})", c.exit_code, (c.run_dir / "run.log").string()));
    std::fflush(stdout);
    if (settings.after_each) settings.after_each();
  }
  // A resumed case took the time of all its parts.
  for (CaseRun& c : cases)
    if (c.start == Start::FromCheckpoint)
      c.wall_seconds = summary_wall(read_summary(c.run_dir)).value_or(c.wall_seconds);
}

}  // namespace ddafrac::app
