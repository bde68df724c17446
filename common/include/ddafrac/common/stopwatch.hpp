#pragma once
// Wall time between two points of a program, for the timings that reports print.

#include <chrono>

namespace ddafrac::common {

/// Seconds of wall time since `start` (a steady clock: not moved by clock changes).
inline double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace ddafrac::common
