// `ddafrac study stability [--out DIR] [--threads N] [--cases name,...]`: the stability study
// over stiff and extreme cases (issue 6). Work in progress: the options are registered, the
// cases come with the ddafrac_stability library.

#include <CLI/CLI.hpp>

#include <memory>
#include <string>
#include <vector>

#include "commands.hpp"

namespace ddafrac::app {

namespace {

struct StabilityArguments {
  std::string out = "runs/study/stability";
  int threads = 0;
  std::vector<std::string> cases;
};

}  // namespace

void register_study_stability(CLI::App& study) {
  auto args = std::make_shared<StabilityArguments>();
  CLI::App* command = study.add_subcommand("stability", "run the stiff and extreme cases and tabulate their stability");
  command->add_option("--out", args->out, "output directory for stability.csv and stability.md")->capture_default_str();
  command->add_option("--threads", args->threads, "OpenMP threads (default: OMP_NUM_THREADS or all cores)")
      ->check(CLI::PositiveNumber);
  command->add_option("--cases", args->cases, "run only these cases (comma-separated names)")->delimiter(',');
  command->callback([] { throw CommandFailed("study stability: not implemented yet"); });
}

}  // namespace ddafrac::app
