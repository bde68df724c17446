// `ddafrac study ...`: the studies of the comparison layer, one subcommand each.
// `study stability` needs no deal.II and is always there; the FEM studies (mesh convergence,
// penalty) register themselves below when the FEM part is built.

#include <CLI/CLI.hpp>

#include "commands.hpp"

namespace ddafrac::app {

void register_study_command(CLI::App& app) {
  CLI::App* study =
      app.add_subcommand("study", "studies: stability over stiff and extreme cases (and, with the FEM, convergence)");
  study->require_subcommand(1);
  register_study_stability(*study);  // study_stability.cpp
  register_study_source(*study);     // study_source.cpp
  register_study_sensitivity(*study);  // study_sensitivity.cpp
#ifdef DDAFRAC_WITH_FEM
  register_study_convergence(*study);  // study_convergence.cpp
  register_study_penalty(*study);      // study_penalty.cpp
#endif
}

}  // namespace ddafrac::app
