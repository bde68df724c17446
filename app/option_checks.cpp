#include "option_checks.hpp"

#include <CLI/CLI.hpp>
#include <fmt/core.h>

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

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& text) -> std::string {
        char* end = nullptr;
        const double value = std::strtod(text.c_str(), &end);
        const bool number = !text.empty() && end && *end == '\0';
        if (number && std::isfinite(value) && value > 0.0) return {};
        return fmt::format("expected a number > 0, got \"{}\"", text);
      },
      "a number > 0");
}

}  // namespace ddafrac::app
