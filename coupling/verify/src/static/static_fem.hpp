#pragma once
// The FEM reference of the static comparison: the same disc under the same pressure (P-degree
// triangles of size D/kFemElementsPerDiameter, the bottom flat of a flattened disc on rollers).

#include <cstddef>
#include <optional>

#include "ddafrac/coupling/verify.hpp"
#include "ddafrac/fem/static_problem.hpp"
#include "ddafrac/reference/analytic.hpp"
#include "static/static_setup.hpp"

namespace ddafrac::coupling {

struct StaticFemRun {
  std::optional<fem::StaticSolution> solution;
  double wall = 0.0;  // s, meshing included
  std::size_t dofs = 0, cells = 0;
  int iterations = 0;         // CG
  double element_size = 0.0;  // m
};

StaticFemRun run_static_fem(const scene::Scene& scene, const StaticSetup& setup, const VerifyOptions& options);

/// FEM stress at a point; a point just outside the FEM's polygonal rim is pulled towards the
/// centre (by kFemPullStep of its radius at a time, at most kFemPullSteps times); none if still
/// outside (inside a slit).
std::optional<reference::Stress2> fem_stress_at(const fem::StaticSolution& solution, double x, double y);

inline constexpr double kFemPullStep = 1e-3;
inline constexpr int kFemPullSteps = 5;

}  // namespace ddafrac::coupling
