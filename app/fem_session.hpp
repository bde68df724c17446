#pragma once
// MPI/Trilinos start-up for the commands that run the FEM (deal.II wants argc/argv; CLI11 has
// already parsed the real ones, so a plain "ddafrac" is passed). Construct one at the top of
// the command's callback; it lives for the command.

#include "ddafrac/fem/environment.hpp"

namespace ddafrac::app {

class FemSession {
 public:
  FemSession() : environment_(argc_, argv_) {}
  FemSession(const FemSession&) = delete;
  FemSession& operator=(const FemSession&) = delete;

 private:
  int argc_ = 1;
  char name_[8] = "ddafrac";
  char* storage_[2] = {name_, nullptr};
  char** argv_ = storage_;
  fem::Environment environment_;  // declared last: built after the arguments above
};

}  // namespace ddafrac::app
