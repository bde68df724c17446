#pragma once
// Small fixed-size algebra types of the DDA engine (six unknowns per block).

#include <Eigen/Core>

#include <cstdint>

namespace ddafrac::dda {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Vec6 = Eigen::Matrix<double, 6, 1>;
using Mat6 = Eigen::Matrix<double, 6, 6>;
using Mat26 = Eigen::Matrix<double, 2, 6>;

/// Index of a block, vertex, contact or joint. Signed so that -1 can mean "none".
using Index = std::int32_t;

/// Block unknown positions inside a Vec6: D = (u0, v0, r0, ex, ey, gxy).
enum Dof : int { kU = 0, kV = 1, kR = 2, kEx = 3, kEy = 4, kGxy = 5 };

}  // namespace ddafrac::dda
