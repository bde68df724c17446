#include "ddafrac/dda/linear_system.hpp"

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <algorithm>
#include <cmath>

#include "deterministic_sum.hpp"

namespace ddafrac::dda {

const char* to_string(SolverKind s) { return s == SolverKind::Pcg ? "pcg-block-jacobi" : "eigen-simplicial-ldlt"; }

void index_nonzero_pairs(BlockMatrix& k, const ContactSet& t) {
  // One serial pass over the pairs in list order, scattering each nonzero pair into the rows of
  // its two blocks: each row lists its pairs ascending, as ContactSet::block_pairs does.
  const std::size_t n = k.diag.size();
  k.row_offsets.assign(n + 1, 0);
  for (std::size_t p = 0; p < t.pairs.size(); ++p)
    if (k.off_nonzero[p]) {
      ++k.row_offsets[static_cast<std::size_t>(t.pairs[p].a) + 1];
      ++k.row_offsets[static_cast<std::size_t>(t.pairs[p].b) + 1];
    }
  for (std::size_t i = 0; i < n; ++i) k.row_offsets[i + 1] += k.row_offsets[i];
  k.row_pairs.resize(static_cast<std::size_t>(k.row_offsets[n]));
  k.row_others.resize(static_cast<std::size_t>(k.row_offsets[n]));
  std::vector<Index> fill(k.row_offsets.begin(), k.row_offsets.end() - 1);
  for (std::size_t p = 0; p < t.pairs.size(); ++p) {
    if (!k.off_nonzero[p]) continue;
    const ContactPair& pr = t.pairs[p];
    const auto at_a = static_cast<std::size_t>(fill[static_cast<std::size_t>(pr.a)]++);
    const auto at_b = static_cast<std::size_t>(fill[static_cast<std::size_t>(pr.b)]++);
    k.row_pairs[at_a] = k.row_pairs[at_b] = static_cast<Index>(p);
    k.row_others[at_a] = pr.b;
    k.row_others[at_b] = pr.a;
  }
}

double dot(const BlockVector& a, const BlockVector& b) {
  return detail::chunked_sum(static_cast<std::int64_t>(a.size()), [&](std::int64_t i) { return a[i].dot(b[i]); });
}

namespace {

/// K's nonzero off-diagonal blocks in product order (SolverWorkspace::row_blocks).
void copy_row_blocks(const BlockMatrix& k, std::vector<Mat6>& row_blocks) {
  const auto entries = static_cast<std::int64_t>(k.row_pairs.size());
  row_blocks.resize(k.row_pairs.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t m = 0; m < entries; ++m) row_blocks[m] = k.off[k.row_pairs[m]];
}

/// y = K x, parallel over block rows (each row gathers its nonzero pairs in the fixed list order).
void multiply(const BlockMatrix& k, const std::vector<Mat6>& row_blocks, const BlockVector& x, BlockVector& y) {
  const auto n = static_cast<std::int64_t>(x.size());
  y.resize(x.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    Vec6 acc = k.diag[i] * x[i];
    for (Index m = k.row_offsets[i]; m < k.row_offsets[i + 1]; ++m) {
      const Index other = k.row_others[m];
      // K_ab is stored for a < b: the row of a uses it, the row of b its transpose.
      if (other > i)
        acc.noalias() += row_blocks[m] * x[other];
      else
        acc.noalias() += row_blocks[m].transpose() * x[other];
    }
    y[i] = acc;
  }
}

SolveReport solve_pcg(const BlockMatrix& k, const BlockVector& b, BlockVector& x, const SolverSettings& cfg,
                      SolverWorkspace& w) {
  const auto n = static_cast<std::int64_t>(b.size());
  SolveReport rep;
  w.r.resize(b.size());
  w.z.resize(b.size());
  w.p.resize(b.size());
  w.q.resize(b.size());
  const bool all_changed = w.preconditioner.size() != b.size() || k.diag_changed.size() != b.size();
  w.preconditioner.resize(b.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i)
    if (all_changed || k.diag_changed[i]) w.preconditioner[i] = k.diag[i].llt().solve(Mat6::Identity());
  const double bnorm = std::sqrt(dot(b, b));
  if (bnorm == 0.0) {
    std::fill(x.begin(), x.end(), Vec6::Zero());
    rep.converged = true;
    return rep;
  }
  copy_row_blocks(k, w.row_blocks);
  multiply(k, w.row_blocks, x, w.q);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    w.r[i] = b[i] - w.q[i];
    w.z[i] = w.preconditioner[i] * w.r[i];
    w.p[i] = w.z[i];
  }
  double rz = dot(w.r, w.z);
  double rnorm = std::sqrt(dot(w.r, w.r));
  const double target = cfg.tolerance * bnorm;
  int it = 0;
  while (rnorm > target && it < cfg.max_iterations) {
    multiply(k, w.row_blocks, w.p, w.q);
    const double pq = dot(w.p, w.q);
    if (!(pq > 0.0)) break;  // not positive definite (or NaN): give up, caller reports it
    const double alpha = rz / pq;
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) {
      x[i] += alpha * w.p[i];
      w.r[i] -= alpha * w.q[i];
      w.z[i] = w.preconditioner[i] * w.r[i];
    }
    const double rz_new = dot(w.r, w.z);
    rnorm = std::sqrt(dot(w.r, w.r));
    const double beta = rz_new / rz;
    rz = rz_new;
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) w.p[i] = w.z[i] + beta * w.p[i];
    ++it;
  }
  rep.iterations = it;
  rep.relative_residual = rnorm / bnorm;
  rep.converged = rnorm <= target && std::isfinite(rnorm);
  return rep;
}

SolveReport solve_direct(const BlockMatrix& k, const ContactSet& t, const BlockVector& b, BlockVector& x) {
  const auto nb = static_cast<Eigen::Index>(b.size());
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<std::size_t>(36 * nb) + 72 * t.pairs.size());
  for (Eigen::Index i = 0; i < nb; ++i)
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) trip.emplace_back(6 * i + r, 6 * i + c, k.diag[static_cast<std::size_t>(i)](r, c));
  for (std::size_t p = 0; p < t.pairs.size(); ++p) {
    const Eigen::Index a = t.pairs[p].a, bb = t.pairs[p].b;
    // Zero blocks stay in the pattern: the fill-reducing ordering depends on it.
    const bool nonzero = k.off_nonzero[p] != 0;
    for (int r = 0; r < 6; ++r)
      for (int c = 0; c < 6; ++c) {
        const double value = nonzero ? k.off[p](r, c) : 0.0;
        trip.emplace_back(6 * a + r, 6 * bb + c, value);
        trip.emplace_back(6 * bb + c, 6 * a + r, value);
      }
  }
  Eigen::SparseMatrix<double> m(6 * nb, 6 * nb);
  m.setFromTriplets(trip.begin(), trip.end());
  Eigen::VectorXd rhs(6 * nb);
  for (Eigen::Index i = 0; i < nb; ++i) rhs.segment<6>(6 * i) = b[static_cast<std::size_t>(i)];
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> ldlt(m);
  SolveReport rep;
  if (ldlt.info() != Eigen::Success) return rep;
  const Eigen::VectorXd sol = ldlt.solve(rhs);
  for (Eigen::Index i = 0; i < nb; ++i) x[static_cast<std::size_t>(i)] = sol.segment<6>(6 * i);
  const double bn = rhs.norm();
  rep.relative_residual = bn > 0 ? (m * sol - rhs).norm() / bn : 0.0;
  rep.converged = std::isfinite(rep.relative_residual);
  return rep;
}

}  // namespace

SolveReport solve(const BlockMatrix& k, const ContactSet& t, const BlockVector& b, BlockVector& x,
                  const SolverSettings& settings, SolverWorkspace& work) {
  x.resize(b.size(), Vec6::Zero());
  if (settings.kind == SolverKind::Direct) return solve_direct(k, t, b, x);
  return solve_pcg(k, b, x, settings, work);
}

}  // namespace ddafrac::dda
