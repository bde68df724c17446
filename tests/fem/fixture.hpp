#pragma once
// Boost.Test global fixture that starts MPI/Trilinos (deal.II) once per test program.

#include <boost/test/unit_test.hpp>

#include <memory>

#include "ddafrac/fem/environment.hpp"

namespace ddafrac::test {

struct FemEnvironment {
  FemEnvironment() {
    auto& suite = boost::unit_test::framework::master_test_suite();
    env = std::make_unique<fem::Environment>(suite.argc, suite.argv);
  }
  std::unique_ptr<fem::Environment> env;
};

}  // namespace ddafrac::test
