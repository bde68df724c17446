#include "option_checks.hpp"

#include <fmt/core.h>
#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>

namespace ddafrac::app {

namespace {

std::string whole_number_range(long long min, long long max) {
  if (max == kNoUpperLimit) return fmt::format("a whole number >= {}", min);
  return fmt::format("a whole number in [{}, {}]", min, max);
}

}  // namespace

CLI::Validator whole_number(long long min, long long max) {
  const std::string expected = whole_number_range(min, max);
  return CLI::Validator(
      [min, max, expected](std::string& text) -> std::string {
        errno = 0;
        char* end = nullptr;
        const long long value = std::strtoll(text.c_str(), &end, 10);
        const bool whole = !text.empty() && end && *end == '\0' && errno != ERANGE;
        if (whole && value >= min && value <= max) return {};
        return fmt::format("expected {}, got \"{}\"", expected, text);
      },
      expected);
}

namespace {

/// A finite number > 0, or >= 0 with `zero_allowed`.
CLI::Validator number_from_zero(bool zero_allowed) {
  const char* const expected = zero_allowed ? "a number >= 0" : "a number > 0";
  return CLI::Validator(
      [zero_allowed, expected](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool number = !text.empty() && end && *end == '\0';
        if (number && std::isfinite(value) && (value > 0.0 || (zero_allowed && value == 0.0))) return {};
        return fmt::format("expected {}, got \"{}\"", expected, text);
      },
      expected);
}

}  // namespace

CLI::Validator positive_number() { return number_from_zero(false); }

CLI::Validator non_negative_number() { return number_from_zero(true); }

CLI::Option* add_dda_threads_option(CLI::App& command, int& threads) {
  return command.add_option("--threads", threads, "OpenMP threads of the DDA")
      ->check(whole_number(1, kMaxThreads))
      ->capture_default_str();
}

CLI::Option* add_fem_degree_option(CLI::App& command, const std::string& name, int& degree) {
  return command.add_option(name, degree, "FEM polynomial degree (1 or 2)")
      ->check(CLI::Range(1, 2))
      ->capture_default_str();
}

}  // namespace ddafrac::app
