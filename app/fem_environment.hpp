#pragma once
// MPI/Trilinos start-up for the commands that use the FEM (fem, verify, study convergence):
// one fem::Environment for the command's lifetime, started without the command's own argv
// (CLI11 has already parsed it; MPI takes its settings from mpirun's environment).

#include <memory>

#include "ddafrac/fem/environment.hpp"

namespace ddafrac::app {

inline std::unique_ptr<fem::Environment> start_fem_environment() {
  static char name[] = "ddafrac";
  static char* argv_storage[] = {name, nullptr};
  int argc = 1;
  char** argv = argv_storage;
  return std::make_unique<fem::Environment>(argc, argv);
}

}  // namespace ddafrac::app
