#include "direct_solver.hpp"

#include <Epetra_CrsMatrix.h>
#include <cholmod.h>

#include <algorithm>
#include <utility>
#include <vector>

namespace ddafrac::fem::detail {

struct DirectSolver::Factor {
  cholmod_common common;
  cholmod_factor* factor = nullptr;
  // Workspaces of cholmod_solve2, allocated by the first solve and reused.
  cholmod_dense* b = nullptr;
  cholmod_dense* x = nullptr;
  cholmod_dense* y = nullptr;
  cholmod_dense* e = nullptr;

  Factor() { cholmod_start(&common); }
  ~Factor() {
    for (cholmod_dense** d : {&b, &x, &y, &e}) cholmod_free_dense(d, &common);
    cholmod_free_factor(&factor, &common);
    cholmod_finish(&common);
  }
  Factor(const Factor&) = delete;
  Factor& operator=(const Factor&) = delete;
};

namespace {

/// The upper triangle of a symmetric matrix in compressed columns (CHOLMOD's stype = 1): column
/// j of the upper triangle is row j of the lower one, read row by row.
cholmod_sparse* upper_triangle(const Matrix& matrix, cholmod_common& common) {
  const Epetra_CrsMatrix& epetra = matrix.trilinos_matrix();
  const auto n = static_cast<std::size_t>(epetra.NumMyRows());
  std::vector<std::pair<int, double>> row;
  std::vector<int> starts{0}, rows;
  std::vector<double> values;
  for (int j = 0; j < static_cast<int>(n); ++j) {
    int count = 0;
    double* entries = nullptr;
    int* columns = nullptr;
    epetra.ExtractMyRowView(j, count, entries, columns);
    const int global_row = epetra.GRID(j);
    row.clear();
    for (int k = 0; k < count; ++k) {
      const int i = epetra.GCID(columns[k]);
      if (i <= global_row) row.emplace_back(i, entries[k]);
    }
    std::sort(row.begin(), row.end());
    for (const auto& [i, value] : row) {
      rows.push_back(i);
      values.push_back(value);
    }
    starts.push_back(static_cast<int>(rows.size()));
  }
  cholmod_sparse* a = cholmod_allocate_sparse(n, n, values.size(), /*sorted=*/1, /*packed=*/1,
                                              /*stype=*/1, CHOLMOD_REAL, &common);
  if (!a) throw FemError("CHOLMOD could not allocate the matrix");
  std::copy(starts.begin(), starts.end(), static_cast<int*>(a->p));
  std::copy(rows.begin(), rows.end(), static_cast<int*>(a->i));
  std::copy(values.begin(), values.end(), static_cast<double*>(a->x));
  return a;
}

}  // namespace

DirectSolver::DirectSolver(const Matrix& matrix) : factor_(std::make_unique<Factor>()) {
  if (!single_rank()) throw FemError("the direct solver needs the whole matrix on one rank");
  cholmod_common& common = factor_->common;
  common.supernodal = CHOLMOD_SIMPLICIAL;  // its triangular solves are the fastest at this size
  common.final_ll = 0;                     // keep L D L^T
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_METIS;
  cholmod_sparse* a = upper_triangle(matrix, common);
  factor_->factor = cholmod_analyze(a, &common);
  if (factor_->factor) cholmod_factorize(a, factor_->factor, &common);
  const bool positive = common.status == CHOLMOD_OK;
  cholmod_free_sparse(&a, &common);
  if (!factor_->factor || !positive)
    throw FemError("CHOLMOD could not factorise the matrix (not positive definite?)");
}

DirectSolver::~DirectSolver() = default;

void DirectSolver::solve(Vec& x, const Vec& b) {
  Factor& f = *factor_;
  const std::size_t n = b.size();
  if (!f.b) f.b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &f.common);
  std::copy(b.begin(), b.end(), static_cast<double*>(f.b->x));
  if (!cholmod_solve2(CHOLMOD_A, f.factor, f.b, nullptr, &f.x, nullptr, &f.y, &f.e, &f.common))
    throw FemError("CHOLMOD solve failed");
  const auto* solution = static_cast<const double*>(f.x->x);
  std::copy(solution, solution + n, x.begin());
}

}  // namespace ddafrac::fem::detail
