// `ddafrac study stability [--out DIR] [--threads N] [--cases name,...]`: the stability study over
// stiff and extreme cases (issue 6). Runs the cases of coupling/stability.hpp one
// after another in this process, prints a line per case, and writes stability.csv and
// stability.md whole. Exit status 0 when every case ends as expected (the impossible one failing
// cleanly with its message), 1 otherwise.

#include <fmt/core.h>
#include <omp.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"
#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/coupling/stability.hpp"
#include "option_checks.hpp"

namespace ddafrac::app {

namespace {

struct StabilityArguments {
  std::string out = "runs/study/stability";
  int threads = 0;
  std::vector<std::string> cases;
};

void run_study_stability(const StabilityArguments& args) {
  std::vector<coupling::StabilityCase> all = coupling::stability_cases();
  std::vector<coupling::StabilityCase> chosen;
  if (args.cases.empty()) {
    chosen = all;
  } else {
    for (const std::string& name : args.cases) {
      const auto it = std::find_if(all.begin(), all.end(), [&](const auto& c) { return c.name == name; });
      if (it == all.end()) {
        std::string names;
        for (const auto& c : all) names += (names.empty() ? "" : ", ") + c.name;
        throw CommandFailed(fmt::format("study stability: no case named '{}'; the cases are: {}", name, names));
      }
      chosen.push_back(*it);
    }
  }
  if (args.threads > 0) omp_set_num_threads(args.threads);
  const int threads = omp_get_max_threads();
  const std::filesystem::path out(args.out);
  std::filesystem::create_directories(out);
  const std::filesystem::path scenes = std::filesystem::path(DDAFRAC_SOURCE_DIR) / "scenes";
  fmt::print("stability study: {} case(s), {} thread(s) -> {}\n", chosen.size(), threads, out.string());
  std::fflush(stdout);

  std::vector<coupling::StabilityResult> results;
  auto write_tables = [&] {
    common::write_whole_text(out / "stability.csv", coupling::stability_csv(results));
    common::write_whole_text(out / "stability.md", coupling::stability_markdown(results));
  };
  for (std::size_t k = 0; k < chosen.size(); ++k) {
    const auto& c = chosen[k];
    fmt::print("[{}/{}] {}: {} ...\n", k + 1, chosen.size(), c.name, c.extreme);
    std::fflush(stdout);
    auto progress = [](const coupling::StabilityProgress& p) {
      fmt::print("      step {}, t = {:.4g} of {:.4g} s, {:.0f} s\n", p.step, p.time, p.end_time, p.wall);
      std::fflush(stdout);
    };
    results.push_back(coupling::run_stability_case(c, scenes, progress));
    const auto& r = results.back();
    fmt::print(
        "      {} blocks, {} steps, end {}, E/S max {:.3f}, penetration {:.2g} of {:.2g} m, cuts {}/{}/{}, "
        "{:.1f} s: {}{}\n",
        r.blocks, r.steps, r.end_reached ? "reached" : "not reached", r.energy_ratio, r.penetration_max,
        r.penetration_allowed, r.cuts_displacement, r.cuts_open_close, r.cuts_solver, r.wall, r.verdict_text,
        r.as_expected ? "" : "  <- NOT AS EXPECTED");
    if (r.exit_status != 0) fmt::print("      {}\n", r.message);
    std::fflush(stdout);
    write_tables();  // after every case: an interrupted study leaves the cases done so far
  }
  fmt::print("wrote {}/{{stability.csv, stability.md}}\n", out.string());
  std::string unexpected;
  for (const auto& r : results)
    if (!r.as_expected) unexpected += (unexpected.empty() ? "" : ", ") + r.name;
  if (!unexpected.empty()) throw CommandFailed("study stability: not as expected: " + unexpected);
}

}  // namespace

void register_study_stability(CLI::App& study) {
  auto args = std::make_shared<StabilityArguments>();
  CLI::App* command = study.add_subcommand("stability", "run the stiff and extreme cases and tabulate their stability");
  command->add_option("--out", args->out, "output directory for stability.csv and stability.md")->capture_default_str();
  command->add_option("--threads", args->threads, "OpenMP threads (default: OMP_NUM_THREADS or all cores)")
      ->check(whole_number(1, kMaxThreads));
  command->add_option("--cases", args->cases, "run only these cases (comma-separated names)")->delimiter(',');
  command->callback([args] { run_study_stability(*args); });
}

}  // namespace ddafrac::app
