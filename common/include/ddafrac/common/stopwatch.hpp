#pragma once
// Wall time between two points of a program, for the timings that reports print.

#include <fmt/core.h>

#include <chrono>
#include <string>

namespace ddafrac::common {

/// Seconds of wall time since `start` (a steady clock: not moved by clock changes).
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

/// A time left or taken, as people read it: "42s", "7m05s", "1h18m"; "--" if unknown (negative,
/// not a number, or beyond four months: an estimate from a run that has barely started).
inline std::string duration_text(double seconds) {
  constexpr double kLongest = 1e7;  // s
  if (!(seconds >= 0.0) || seconds > kLongest) return "--";
  const long s = static_cast<long>(seconds);
  if (s >= 3600) return fmt::format("{}h{:02d}m", s / 3600, static_cast<int>((s % 3600) / 60));
  if (s >= 60) return fmt::format("{}m{:02d}s", s / 60, static_cast<int>(s % 60));
  return fmt::format("{}s", s);
}

}  // namespace ddafrac::common
