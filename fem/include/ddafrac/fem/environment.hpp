#pragma once
// MPI (and Trilinos) start-up for any program that uses the FEM: construct one Environment
// at the top of main() (or in a test's global fixture) before any FEM call.

#include <memory>

namespace ddafrac::fem {

class Environment {
 public:
  Environment(int& argc, char**& argv);
  ~Environment();
  Environment(const Environment&) = delete;
  Environment& operator=(const Environment&) = delete;

  static int rank();
  static int size();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace ddafrac::fem
