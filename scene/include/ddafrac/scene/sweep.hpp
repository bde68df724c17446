#pragma once
// A sweep: a set of scene files run as one study (the 15 impact cases, say), with one table of
// results. Read from a small TOML file, validated like a scene.

#include <filesystem>
#include <string>
#include <vector>

namespace ddafrac::scene {

/// More simultaneous runs, or more OpenMP threads per run, than these is taken for a typo (the
/// command-line options --parallel and --threads share the bounds).
inline constexpr long long kMaxParallelRuns = 256;
inline constexpr long long kMaxThreadsPerRun = 1024;

struct Sweep {
  std::string name;
  std::filesystem::path source;              // the sweep file
  std::vector<std::filesystem::path> cases;  // scene files, resolved against the sweep file
  std::vector<std::string> overrides;        // `--set` values applied to every case
  double crack_time = 0.0;                   // s: the table reports crack counts at this time
  int parallel = 0;                          // runs at once; 0 = as many as the cores allow
  int threads = 1;                           // OpenMP threads of each run
};

/// Reads and validates a sweep file; throws SceneError (parse.hpp) listing every problem.
Sweep load_sweep(const std::filesystem::path& path);

}  // namespace ddafrac::scene
