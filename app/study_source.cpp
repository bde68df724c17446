// `ddafrac study source [--out DIR] [--resume] [--status] [--set key=value ...] [--parallel N]
// [--cases name,...]`: the source study as one resumable command. Runs the flattened discs, the
// pre-cracked discs and the 15 impact cases, each as its own `ddafrac run` process (the sweep's
// machinery, case_runs.hpp, driven as every study is, study_runs.hpp), then writes study.md,
// study.csv and the series' figures.

#include <CLI/CLI.hpp>

#include <memory>

#include "commands.hpp"
#include "study_runs.hpp"
#include "study_source_report.hpp"

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;

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

std::vector<StudyCase> load_study(const std::vector<std::string>& overrides, const fs::path& out) {
  const fs::path scenes = fs::path(DDAFRAC_SOURCE_DIR) / "scenes";
  std::vector<fs::path> files;
  std::vector<std::string> series;
  for (const Series& s : kSeries)
    for (const char* scene : s.scenes) {
      files.push_back(scenes / scene);
      series.emplace_back(s.name);
    }
  std::vector<CaseRun> runs = load_case_runs(files, overrides, out, "the study's cases");
  std::vector<StudyCase> all;
  for (std::size_t k = 0; k < runs.size(); ++k) all.push_back({series[k], std::move(runs[k]), {}});
  return all;
}

}  // namespace

void register_study_source(CLI::App& study) {
  auto args = std::make_shared<StudyArguments>();
  CLI::App* command = study.add_subcommand(
      "source", "the source study: flattened and pre-cracked discs, impact cases 1-15, as one resumable command");
  add_study_options(
      *command, *args, "study-source",
      "override a value of every case, e.g. --set mesh.blocks=700 (a reduced study: every scene meshes at 700)",
      [args] {
        const fs::path out(args->out);
        StudyKind kind;
        kind.command = "study source";
        kind.figures_command = "study-source";
        kind.load = [out](const std::vector<std::string>& overrides) { return load_study(overrides, out); };
        kind.markdown = study_markdown;
        return kind;
      });
}

}  // namespace ddafrac::app
