#pragma once
// Internal: a sparse Cholesky factorisation (L D L^T, CHOLMOD of SuiteSparse) of one symmetric
// positive definite matrix, computed once; each solve is then two triangular solves and costs
// the same at every step, whatever the right-hand side. It is the step solver on one MPI rank
// (step_solver.hpp). On several ranks it still works but does not scale: the factor is whole
// on every rank (each gathers the matrix and factorises it), a solve gathers b, every rank
// solves the same system and keeps its own entries of x.

#include <memory>
#include <vector>

#include "model.hpp"

namespace ddafrac::fem::detail {

class DirectSolver {
 public:
  static constexpr const char* name = "sparse Cholesky (CHOLMOD), factorised once";
  /// Gathers the matrix, orders it (METIS nested dissection, which fills least here), analyses
  /// and factorises.
  explicit DirectSolver(const Matrix& matrix);
  ~DirectSolver();
  DirectSolver(const DirectSolver&) = delete;
  DirectSolver& operator=(const DirectSolver&) = delete;

  /// x = A^-1 b.
  void solve(Vec& x, const Vec& b);

 private:
  struct Factor;  // CHOLMOD's state, kept out of this header
  std::unique_ptr<Factor> factor_;
  std::vector<dealii::types::global_dof_index> owned_;  // global index of each local entry
};

}  // namespace ddafrac::fem::detail
