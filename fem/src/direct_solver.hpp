#pragma once
// Internal: a sparse Cholesky factorisation (L D L^T, CHOLMOD of SuiteSparse) of one symmetric
// positive definite matrix, computed once; each solve is then two triangular solves and costs
// the same at every step, whatever the right-hand side. The matrix must be whole on this
// process: one MPI rank only (with more, the caller keeps the distributed CG + AMG).

#include <memory>

#include "model.hpp"

namespace ddafrac::fem::detail {

class DirectSolver {
 public:
  static constexpr const char* name = "sparse Cholesky (CHOLMOD), factorised once";
  /// Orders (METIS nested dissection, which fills least here), analyses and factorises.
  explicit DirectSolver(const Matrix& matrix);
  ~DirectSolver();
  DirectSolver(const DirectSolver&) = delete;
  DirectSolver& operator=(const DirectSolver&) = delete;

  /// x = A^-1 b.
  void solve(Vec& x, const Vec& b);

 private:
  struct Factor;  // CHOLMOD's state, kept out of this header
  std::unique_ptr<Factor> factor_;
};

}  // namespace ddafrac::fem::detail
