// Engine: the linear system of a step (block terms, contact assembly) and the open-close judgement.
#include "ddafrac/dda/engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/geometry.hpp"
#include "deterministic_sum.hpp"

namespace ddafrac::dda {

namespace {
/// k += s·a·bᵀ, each entry as (s·a_i)·b_j — the same operations, in the same order, as Eigen's
/// `k.noalias() += s * a * b.transpose()`, so the sums are bit for bit the same — written out
/// so that the compiler inlines it: the assembly makes up to six such updates per contact, and
/// Eigen's generic product loop stayed an out-of-line call.
inline void add_outer_product(Mat6& k, double s, const Vec6& a, const Vec6& b) {
  const Vec6 sa = s * a;
  for (int j = 0; j < 6; ++j) k.col(j) += sa * b[j];
}
}  // namespace

// Inertia, elasticity, initial stress, gravity, point loads and anchors: docs/design.md §3.
void Engine::block_terms(double dt) {
  const auto n = static_cast<std::int64_t>(blocks_.block_count());
  base_diag_.resize(static_cast<std::size_t>(n));
  base_rhs_.resize(static_cast<std::size_t>(n));
  const auto& an = scene_.analysis;
  const double eta = an.mass_damping;
  const double mass_k = 2.0 / (dt * dt) + 2.0 * eta / dt;  // Newmark γ=1, β=½ (+ηM)
  const double mass_f = 2.0 / dt + eta;
  const double t_end = time_ + dt;
  const bool dynamic = active_.dynamic;
  const bool gravity = active_.gravity;
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const PolygonIntegrals& g = blocks_.geometry[i];
    const MaterialData& mat = blocks_.materials[static_cast<std::size_t>(blocks_.material[i])];
    const Mat6 m = (blocks_.mass[i] / g.area) * mass_integral(g);
    Mat6 k = mass_k * m;
    Vec6 f = Vec6::Zero();
    if (dynamic) f.noalias() += mass_f * (m * blocks_.velocity[i]);
    k.block<3, 3>(3, 3) += g.area * mat.elastic;
    f.segment<3>(3) -= g.area * blocks_.stress[i];
    if (gravity) {
      f[kU] += blocks_.mass[i] * an.gravity[0];
      f[kV] += blocks_.mass[i] * an.gravity[1];
    }
    for (Index l = blocks_.load_offsets[i]; l < blocks_.load_offsets[i + 1]; ++l) {
      const PointLoad& p = blocks_.loads[static_cast<std::size_t>(l)];
      const Mat26 t = displacement_matrix(g.cx, g.cy, p.x, p.y);
      f.noalias() += t.transpose() * Eigen::Vector2d(p.fx, p.fy);
    }
    for (Index a = blocks_.anchor_offsets[i]; a < blocks_.anchor_offsets[i + 1]; ++a) {
      const Anchor& p = blocks_.anchors[static_cast<std::size_t>(a)];
      const Mat26 t = displacement_matrix(g.cx, g.cy, p.x, p.y);
      k.noalias() += anchor_penalty_ * t.transpose() * t;
      const Eigen::Vector2d target(p.x_start + p.vx * t_end - p.x, p.y_start + p.vy * t_end - p.y);
      f.noalias() += anchor_penalty_ * t.transpose() * target;
    }
    base_diag_[i] = k;
    base_rhs_[i] = f;
  }
}

void Engine::assemble(bool whole) {
  const auto n = static_cast<std::int64_t>(blocks_.block_count());
  const auto np = static_cast<std::int64_t>(set_.pairs.size());
  const auto nc = static_cast<std::int64_t>(set_.contacts.size());
  const auto& cs = set_.contacts;
  matrix_.diag.resize(static_cast<std::size_t>(n));
  matrix_.off.resize(static_cast<std::size_t>(np));
  matrix_.off_nonzero.resize(static_cast<std::size_t>(np));
  matrix_.diag_changed.resize(static_cast<std::size_t>(n));
  rhs_.resize(static_cast<std::size_t>(n));
  // Coefficients of every contact once, in list order: the gathers below read these small
  // records and pass over open contacts without loading the contacts themselves. Within a step
  // the geometry is fixed, so after the first assembly only the blocks and pairs of contacts
  // whose coefficients changed (state changes, friction loads) are gathered again — with the
  // same code, so the matrix is the one a whole assembly would give, bit for bit.
  coefficients_.resize(static_cast<std::size_t>(nc));
  coefficient_changed_.resize(static_cast<std::size_t>(nc));
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < nc; ++k) {
    const ContactCoefficients q = contact_coefficients(cs[k]);
    const ContactCoefficients& old = coefficients_[k];
    coefficient_changed_[k] =
        whole || q.kn_eff != old.kn_eff || q.ks_eff != old.ks_eff || q.fn_rhs != old.fn_rhs || q.fs_rhs != old.fs_rhs;
    coefficients_[k] = q;
  }
  auto inactive = [](const ContactCoefficients& q) { return q.kn_eff == 0.0 && q.ks_eff == 0.0; };
  // Diagonal blocks and loads: gathered per block from its sorted contact list (no races).
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < n; ++i) {
    const Index first = set_.block_contact_offsets[i], last = set_.block_contact_offsets[i + 1];
    const bool changed = whole || std::any_of(set_.block_contacts.data() + first, set_.block_contacts.data() + last,
                                              [&](Index m) { return coefficient_changed_[m] != 0; });
    matrix_.diag_changed[i] = changed ? 1 : 0;
    if (!changed) continue;
    Mat6 k = base_diag_[i];
    Vec6 f = base_rhs_[i];
    for (Index m = first; m < last; ++m) {
      const ContactCoefficients& q = coefficients_[set_.block_contacts[m]];
      if (inactive(q) && q.fs_rhs == 0.0) continue;
      const Index contact = set_.block_contacts[m];
      const ContactLinearisation& lin = linear_[contact];
      const bool vertex_side = set_.vertex_blocks[contact] == i;
      const Vec6& a = vertex_side ? lin.e : lin.g;
      const Vec6& b = vertex_side ? lin.es : lin.gs;
      if (q.kn_eff != 0.0) add_outer_product(k, q.kn_eff, a, a);
      if (q.ks_eff != 0.0) add_outer_product(k, q.ks_eff, b, b);
      f += q.fn_rhs * a + q.fs_rhs * b;
    }
    matrix_.diag[i] = k;
    rhs_[i] = f;
  }
  // Off-diagonal blocks: each pair owns its block and sums its own contacts in order.
  bool nonzero_pairs_changed = whole;
#pragma omp parallel for schedule(static) reduction(|| : nonzero_pairs_changed)
  for (std::int64_t p = 0; p < np; ++p) {
    const ContactPair& pr = set_.pairs[p];
    if (!whole && std::none_of(coefficient_changed_.data() + pr.first, coefficient_changed_.data() + pr.last,
                               [](std::uint8_t changed) { return changed != 0; }))
      continue;
    // Most pairs of an intact body have only open contacts: found before any block is zeroed.
    const auto first_active = static_cast<Index>(
        std::find_if_not(coefficients_.data() + pr.first, coefficients_.data() + pr.last, inactive) -
        coefficients_.data());
    const bool nonzero = first_active < pr.last;
    if (matrix_.off_nonzero[p] != (nonzero ? 1 : 0)) nonzero_pairs_changed = true;
    matrix_.off_nonzero[p] = nonzero ? 1 : 0;
    if (!nonzero) continue;
    Mat6 k = Mat6::Zero();
    for (Index m = first_active; m < pr.last; ++m) {
      const ContactCoefficients& q = coefficients_[m];
      if (inactive(q)) continue;
      const ContactLinearisation& lin = linear_[m];
      const bool v_is_a = set_.vertex_blocks[m] == pr.a;
      const Vec6& na = v_is_a ? lin.e : lin.g;
      const Vec6& nb = v_is_a ? lin.g : lin.e;
      const Vec6& sa = v_is_a ? lin.es : lin.gs;
      const Vec6& sb = v_is_a ? lin.gs : lin.es;
      if (q.kn_eff != 0.0) add_outer_product(k, q.kn_eff, na, nb);
      if (q.ks_eff != 0.0) add_outer_product(k, q.ks_eff, sa, sb);
    }
    matrix_.off[p] = k;
  }
  if (nonzero_pairs_changed) index_nonzero_pairs(matrix_, set_);
}

bool Engine::judge(int& changed_first) {
  const auto nc = static_cast<std::int64_t>(set_.contacts.size());
  int first = std::numeric_limits<int>::max();
  int changed = 0;
  const double tol = state_band();
#pragma omp parallel for schedule(static) reduction(+ : changed) reduction(min : first)
  for (std::int64_t k = 0; k < nc; ++k) {
    Contact& c = set_.contacts[k];
    if (judge_contact(c, linear_[k], d_[c.vblock], d_[c.eblock], c.held(blocks_.joints), tol)) {
      ++changed;
      first = std::min(first, static_cast<int>(k));
    }
  }
  changed_first = changed > 0 ? first : -1;
  return changed == 0;
}

}  // namespace ddafrac::dda
