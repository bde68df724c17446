// ddafrac: one program, one subcommand per job (mesh, run, bench, fem, ...).

#include <CLI/CLI.hpp>
#include <fmt/core.h>

#include <exception>

#include "commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{"ddafrac: 2D DDA with virtual joints for rock fracture, verified against deal.II FEM"};
  app.require_subcommand(1);
  app.set_version_flag("--version", DDAFRAC_VERSION);

  ddafrac::app::register_mesh_command(app);
  ddafrac::app::register_run_command(app);
  ddafrac::app::register_bench_command(app);
  ddafrac::app::register_sweep_command(app);
  ddafrac::app::register_study_command(app);
#ifdef DDAFRAC_WITH_FEM
  ddafrac::app::register_fem_command(app);
  ddafrac::app::register_verify_command(app);
#endif

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const ddafrac::app::CommandFailed& e) {
    fmt::print(stderr, "ddafrac: {}\n", e.what());
    return e.exit_code();
  } catch (const std::exception& e) {
    fmt::print(stderr, "ddafrac: error: {}\n", e.what());
    return 1;
  }
  return 0;
}
