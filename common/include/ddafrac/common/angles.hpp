#pragma once
// π and the degree, once for the whole tree: scenes give angles in degrees, the code works in
// radians.

namespace ddafrac::common {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kRadiansPerDegree = kPi / 180.0;  // rad per degree

}  // namespace ddafrac::common
