#pragma once
// Each subcommand of `ddafrac` lives in its own file and registers itself on the CLI11 app.
// The callback it installs runs the command and reports failure by throwing CommandFailed
// (message already meant for the user) or any std::exception.

#include <stdexcept>

namespace CLI {
class App;
}

namespace ddafrac::app {

/// A failure that has already been explained to the user; main() prints it and exits with code.
class CommandFailed : public std::runtime_error {
 public:
  CommandFailed(const std::string& message, int exit_code = 1) : std::runtime_error(message), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

void register_mesh_command(CLI::App& app);       // mesh_command.cpp
void register_run_command(CLI::App& app);        // run_command.cpp   (DDA engine)
void register_bench_command(CLI::App& app);      // bench_command.cpp (DDA benchmark)
void register_sweep_command(CLI::App& app);      // sweep_command.cpp (many runs, one table)
void register_study_command(CLI::App& app);      // study_command.cpp (`ddafrac study`, parent of the studies)
void register_study_stability(CLI::App& study);  // study_stability.cpp (`ddafrac study stability`)
void register_study_source(CLI::App& study);     // study_source.cpp (`ddafrac study source`)
void register_study_sensitivity(CLI::App& study);  // study_sensitivity.cpp (`ddafrac study sensitivity`)
#ifdef DDAFRAC_WITH_FEM
void register_fem_command(CLI::App& app);          // fem_command.cpp   (deal.II reference)
void register_verify_command(CLI::App& app);       // verify_command.cpp (DDA vs FEM vs analytic, PASS/FAIL)
void register_study_convergence(CLI::App& study);  // study_convergence.cpp (`ddafrac study convergence`)
void register_study_penalty(CLI::App& study);      // study_penalty.cpp (`ddafrac study penalty`)
#endif

}  // namespace ddafrac::app
