#pragma once
// Internal: the linear solver of the Newmark step, (K + c_u M) u_new = rhs. The matrix does
// not change at a fixed dt, so each solver does its expensive part (factorisation or AMG
// hierarchy) once, and a step costs only the solve.

#include <memory>

#include "ddafrac/fem/dynamic_problem.hpp"
#include "model.hpp"

namespace ddafrac::fem::detail {

class StepSolver {
 public:
  virtual ~StepSolver() = default;
  /// x = A^-1 b; x holds the previous step's solution on entry (a warm start for CG). Returns
  /// the iteration count (0 for a direct solve).
  virtual int solve(Vec& x, const Vec& b) = 0;
  virtual const char* name() const = 0;
};

/// The solver of `kind` for `matrix`, which must outlive it. `automatic`: CHOLMOD on one rank
/// (the fastest there), MUMPS on more (distributed, the same answer to round-off).
std::unique_ptr<StepSolver> make_step_solver(StepSolverKind kind, const Matrix& matrix, const Model& model,
                                             const SolverSettings& cg);

}  // namespace ddafrac::fem::detail
