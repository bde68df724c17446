// ddafrac: one program, one subcommand per job (mesh, run, bench, fem, ...).

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <CLI/CLI.hpp>

#include <algorithm>
#include <exception>
#include <new>
#include <string>
#include <vector>

#include "commands.hpp"
#include "ddafrac/build_commit.hpp"

namespace {

std::vector<std::string> command_names(CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* command : app.get_subcommands([](CLI::App*) { return true; }))
    names.push_back(command->get_name());
  return names;
}

/// CLI11 answers a missing or misspelt command (or a study's) with only "A subcommand is
/// required": say which word was not a command and list the commands. Returns the exit status,
/// or 0 if all is well.
int check_command_words(CLI::App& app, int argc, char** argv) {
  CLI::App* level = &app;
  std::string path = "ddafrac";
  for (int i = 1;; ++i) {
    const std::vector<std::string> names = command_names(*level);
    const std::string word = i < argc ? argv[i] : "";
    if (names.empty() || (!word.empty() && word[0] == '-')) return 0;  // options, --help: CLI11's own
    if (std::find(names.begin(), names.end(), word) != names.end()) {
      level = level->get_subcommand(word);
      path += " " + word;
      continue;
    }
    const std::string list = fmt::format("{}", fmt::join(names, ", "));
    if (word.empty())
      fmt::print(stderr, "{}: a command is required; the commands are: {} ({} --help)\n", path, list, path);
    else
      fmt::print(stderr, "{}: unknown command \"{}\"; the commands are: {} ({} --help)\n", path, word, list, path);
    return static_cast<int>(CLI::ExitCodes::RequiredError);
  }
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ddafrac: 2D DDA with virtual joints for rock fracture, verified against deal.II FEM"};
  app.require_subcommand(1);
  app.set_version_flag("--version", DDAFRAC_VERSION " (commit " DDAFRAC_COMMIT ", " DDAFRAC_ARCH ")");

  ddafrac::app::register_mesh_command(app);
  ddafrac::app::register_run_command(app);
  ddafrac::app::register_bench_command(app);
  ddafrac::app::register_sweep_command(app);
  ddafrac::app::register_study_command(app);
#ifdef DDAFRAC_WITH_FEM
  ddafrac::app::register_fem_command(app);
  ddafrac::app::register_verify_command(app);
#endif

  if (const int status = check_command_words(app, argc, argv)) return status;
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ddafrac::app::CommandFailed& e) {
    fmt::print(stderr, "ddafrac: {}\n", e.what());
    return e.exit_code();
  } catch (const std::bad_alloc&) {
    fmt::print(stderr, "ddafrac: out of memory: the model needs more memory than this machine has available\n");
    return 1;
  } catch (const std::exception& e) {
    fmt::print(stderr, "ddafrac: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
