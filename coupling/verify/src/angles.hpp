#pragma once
// π for the comparisons' geometry and the degrees of their reports.

namespace ddafrac::coupling {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace ddafrac::coupling
