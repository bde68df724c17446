#pragma once
// Checks of numeric command-line values that name the option, what it expects and what was
// typed ("--threads: expected a whole number >= 1, got 0"), in place of CLI11's own range
// checks, whose message prints the largest double in full (309 digits); and the options that
// several commands declare alike.

#include <limits>
#include <string>

#include "ddafrac/scene/sweep.hpp"

namespace CLI {
class App;
class Option;
class Validator;
}  // namespace CLI

namespace ddafrac::app {

inline constexpr long long kNoUpperLimit = std::numeric_limits<long long>::max();
/// --threads of every command and --parallel of sweep share the bounds of a sweep file.
inline constexpr long long kMaxThreads = scene::kMaxThreadsPerRun;
using scene::kMaxParallelRuns;

/// A whole number in [min, max].
CLI::Validator whole_number(long long min, long long max = kNoUpperLimit);

/// A finite number > 0.
CLI::Validator positive_number();

/// A finite number >= 0.
CLI::Validator non_negative_number();

/// --threads of the commands that run a DDA next to the FEM: the DDA's OpenMP threads.
CLI::Option* add_dda_threads_option(CLI::App& command, int& threads);

/// A FEM polynomial degree option (1 or 2) under `name`, e.g. --degree or --fem-degree.
CLI::Option* add_fem_degree_option(CLI::App& command, const std::string& name, int& degree);

}  // namespace ddafrac::app
