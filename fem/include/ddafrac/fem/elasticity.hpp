#pragma once
// Plain settings and results shared by the static and dynamic FEM problems. No deal.II types
// leak through the public fem headers: the CLI and the comparison layer compile without it.

#include <cstddef>
#include <stdexcept>
#include <string>

#include "ddafrac/reference/analytic.hpp"

namespace ddafrac::fem {

using reference::PlaneModel;
using reference::Stress2;

struct Material {
  reference::Elastic elastic;  // E (Pa), nu, rho (kg/m^3)
  PlaneModel plane = PlaneModel::Stress;
};

/// Element choice: the cell shape comes from the mesh (triangles -> FE_SimplexP with an
/// isoparametric mapping, quadrilaterals -> FE_Q); curved rim groups are kept on the circle.
struct Discretisation {
  int degree = 2;       // 1 or 2
  int refinements = 0;  // uniform refinements of the input mesh (new rim vertices on the circle)
};

struct SolverSettings {
  double relative_tolerance = 1e-10;  // CG stopping criterion |r| <= tol |b|
  int max_iterations = 5000;
};

/// Stress at a point, with the principal values (s1 >= s3, tension positive).
struct StressSample {
  double x = 0.0;  // m
  double y = 0.0;  // m
  Stress2 stress;
  double s1 = 0.0;  // Pa
  double s3 = 0.0;  // Pa
};

StressSample make_sample(double x, double y, const Stress2& stress);

/// What one solve cost.
struct RunStats {
  std::size_t cells = 0;
  std::size_t dofs = 0;
  std::string solver;          // the linear solver used
  int iterations = 0;          // CG iterations (dynamic: summed over the steps; 0 if direct)
  double setup_seconds = 0.0;  // mesh, dofs, assembly, AMG
  double solve_seconds = 0.0;  // CG (+ time loop)
};

/// Thrown for problems the FEM cannot set up (unsupported cells, a missing boundary group,
/// a point outside the body, a solver that did not converge).
class FemError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace ddafrac::fem
