#pragma once
// Symmetric block-sparse system with 6x6 blocks: one diagonal block per DDA block and one
// off-diagonal block per contacting pair (K_ab for a < b; K_ba = K_ab^T is implied).
// Solvers: PCG with 6x6 block-Jacobi preconditioner (warm-started), or Eigen's SimplicialLDLT.
// Every reduction runs over fixed-size chunks summed in order: results do not depend on the
// number of OpenMP threads. The design: docs/design.md §6 (system, solvers) and §10.2.

#include <cstdint>
#include <vector>

#include "ddafrac/dda/contact.hpp"
#include "ddafrac/dda/types.hpp"
#include "ddafrac/scene/defaults.hpp"

namespace ddafrac::dda {

struct BlockMatrix {
  std::vector<Mat6> diag;  // per block
  std::vector<Mat6> off;   // per ContactSet::pairs entry, K_ab with a < b, where off_nonzero
  // Whether a pair's K_ab is nonzero (some contact of the pair closed); where it is 0 the pair's
  // off block is zero and left unwritten, and the product skips it (most pairs of an intact body
  // are open contacts at shared mesh nodes).
  std::vector<std::uint8_t> off_nonzero;
  // Whether a diagonal block changed since the previous solve (the assembly sets it): the
  // preconditioner inverts only those again. Empty: all changed.
  std::vector<std::uint8_t> diag_changed;
  // Per block row, the pairs with a nonzero off block (CSR, in the row's pair order) and the
  // other block of each: the product walks these alone (index_nonzero_pairs).
  std::vector<Index> row_offsets, row_pairs, row_others;
};

/// Fills k.row_* from k.off_nonzero and the topology (after every assembly).
void index_nonzero_pairs(BlockMatrix& k, const ContactSet& topology);

using BlockVector = std::vector<Vec6>;

/// Deterministic dot product (chunked, chunk sums added in order).
double dot(const BlockVector& a, const BlockVector& b);

enum class SolverKind { Pcg, Direct };
const char* to_string(SolverKind s);

struct SolveReport {
  int iterations = 0;            // PCG iterations (0 for the direct solver)
  double relative_residual = 0;  // |b - Kx| / |b|
  bool converged = false;
};

struct SolverSettings {
  SolverKind kind = SolverKind::Pcg;
  double tolerance = scene::kDefaultSolverTolerance;  // PCG's relative residual; an Engine takes its scene's
  int max_iterations = 5000;
};

/// Scratch vectors of PCG, kept between solves.
struct SolverWorkspace {
  BlockVector r, z, p, q;
  std::vector<Mat6> preconditioner;  // inverted diagonal blocks
  // The nonzero off-diagonal blocks in the order the products read them (row by row, each pair
  // twice): PCG's products stream this copy instead of jumping to a row's lower neighbours' pairs.
  std::vector<Mat6> row_blocks;
};

/// Solves K x = b; x holds the warm start on entry.
SolveReport solve(const BlockMatrix& k, const ContactSet& topology, const BlockVector& b, BlockVector& x,
                  const SolverSettings& settings, SolverWorkspace& work);

}  // namespace ddafrac::dda
