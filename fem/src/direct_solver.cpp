#include "direct_solver.hpp"

#include <deal.II/base/mpi.h>

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

/// This rank's rows of the lower triangle of a symmetric matrix, which are its columns of the
/// upper triangle (CHOLMOD's stype = 1), with global indices.
struct Columns {
  std::vector<int> index;   // global index of each column
  std::vector<int> counts;  // entries in each column
  std::vector<int> rows;    // global row of each entry, sorted within a column
  std::vector<double> values;

  template <class Archive>
  void serialize(Archive& archive, unsigned int /*version*/) {
    archive& index& counts& rows& values;
  }
};

Columns owned_upper_columns(const Matrix& matrix) {
  const Epetra_CrsMatrix& epetra = matrix.trilinos_matrix();
  Columns out;
  std::vector<std::pair<int, double>> column;
  for (int j = 0; j < epetra.NumMyRows(); ++j) {
    int count = 0;
    double* entries = nullptr;
    int* local_columns = nullptr;
    epetra.ExtractMyRowView(j, count, entries, local_columns);
    const int global_row = epetra.GRID(j);
    column.clear();
    for (int k = 0; k < count; ++k) {
      const int i = epetra.GCID(local_columns[k]);
      if (i <= global_row) column.emplace_back(i, entries[k]);
    }
    std::sort(column.begin(), column.end());
    out.index.push_back(global_row);
    out.counts.push_back(static_cast<int>(column.size()));
    for (const auto& [i, value] : column) {
      out.rows.push_back(i);
      out.values.push_back(value);
    }
  }
  return out;
}

/// The whole upper triangle in compressed columns, on every rank: each rank's columns gathered.
cholmod_sparse* whole_upper_triangle(const Matrix& matrix, cholmod_common& common) {
  const auto n = static_cast<std::size_t>(matrix.m());
  const std::vector<Columns> parts = dealii::Utilities::MPI::all_gather(MPI_COMM_WORLD, owned_upper_columns(matrix));
  std::vector<int> starts(n + 1, 0);
  std::size_t entries = 0;
  for (const auto& part : parts) {
    for (std::size_t k = 0; k < part.index.size(); ++k) starts[part.index[k] + 1] = part.counts[k];
    entries += part.values.size();
  }
  for (std::size_t j = 0; j < n; ++j) starts[j + 1] += starts[j];
  cholmod_sparse* a = cholmod_allocate_sparse(n, n, entries, /*sorted=*/1, /*packed=*/1,
                                              /*stype=*/1, CHOLMOD_REAL, &common);
  if (!a) throw FemError("CHOLMOD could not allocate the matrix");
  std::copy(starts.begin(), starts.end(), static_cast<int*>(a->p));
  for (const auto& part : parts) {
    std::size_t from = 0;
    for (std::size_t k = 0; k < part.index.size(); ++k) {
      const auto to = static_cast<std::size_t>(starts[part.index[k]]);
      const auto count = static_cast<std::size_t>(part.counts[k]);
      std::copy_n(part.rows.begin() + from, count, static_cast<int*>(a->i) + to);
      std::copy_n(part.values.begin() + from, count, static_cast<double*>(a->x) + to);
      from += count;
    }
  }
  return a;
}

}  // namespace

DirectSolver::DirectSolver(const Matrix& matrix) : factor_(std::make_unique<Factor>()) {
  matrix.locally_owned_range_indices().fill_index_vector(owned_);
  cholmod_common& common = factor_->common;
  common.supernodal = CHOLMOD_SIMPLICIAL;  // its triangular solves are the fastest at this size
  common.final_ll = 0;                     // keep L D L^T
  common.nmethods = 1;
  common.method[0].ordering = CHOLMOD_METIS;
  cholmod_sparse* a = whole_upper_triangle(matrix, common);
  factor_->factor = cholmod_analyze(a, &common);
  if (factor_->factor) cholmod_factorize(a, factor_->factor, &common);
  const bool positive = common.status == CHOLMOD_OK;
  cholmod_free_sparse(&a, &common);
  if (!factor_->factor || !positive) throw FemError("CHOLMOD could not factorise the matrix (not positive definite?)");
}

DirectSolver::~DirectSolver() = default;

void DirectSolver::solve(Vec& x, const Vec& b) {
  Factor& f = *factor_;
  const std::size_t n = b.size();
  if (!f.b) f.b = cholmod_allocate_dense(n, 1, n, CHOLMOD_REAL, &f.common);
  // The whole of b on every rank: each rank puts in its own entries, the sum gathers them.
  auto* whole = static_cast<double*>(f.b->x);
  if (!single_rank()) std::fill(whole, whole + n, 0.0);
  for (std::size_t k = 0; k < owned_.size(); ++k) whole[owned_[k]] = b.begin()[k];
  if (!single_rank()) MPI_Allreduce(MPI_IN_PLACE, whole, static_cast<int>(n), MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  if (!cholmod_solve2(CHOLMOD_A, f.factor, f.b, nullptr, &f.x, nullptr, &f.y, &f.e, &f.common))
    throw FemError("CHOLMOD solve failed");
  const auto* solution = static_cast<const double*>(f.x->x);
  for (std::size_t k = 0; k < owned_.size(); ++k) x.begin()[k] = solution[owned_[k]];
}

}  // namespace ddafrac::fem::detail
