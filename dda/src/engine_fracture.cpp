// Engine: joint forces and the fracture check of virtual joints after each accepted step
// (docs/design.md §5).
#include "ddafrac/dda/engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/geometry.hpp"
#include "deterministic_sum.hpp"

namespace ddafrac::dda {

FailureRatios failure_ratios(const JointForce& f, double length, const scene::JointSet& js) {
  auto ratio = [](double load, double strength) {
    if (load <= 0.0) return 0.0;
    return strength > 0.0 ? load / strength : std::numeric_limits<double>::infinity();
  };
  const double compression = std::max(0.0, -f.normal);
  const JointStrength strength =
      joint_strength(js.tensile_strength, js.cohesion, std::tan(js.friction_angle), length, compression);
  FailureRatios r;
  r.r1 = ratio(f.normal, strength.tension);
  r.r2 = ratio(std::abs(f.shear), strength.shear);
  return r;
}

std::vector<JointForce> Engine::joint_forces() const {
  const auto& js = blocks_.joints;
  const auto& cs = set_.contacts;
  const auto& pairs = set_.pairs;
  std::vector<JointForce> f(js.size());
  const auto nj = static_cast<std::int64_t>(js.size());
  // A joint's contacts lie in the contact range of its block pair (pairs are sorted by (a, b));
  // they are summed in list order, so the sum is the same for any thread count.
#pragma omp parallel for schedule(static)
  for (std::int64_t j = 0; j < nj; ++j) {
    const Joint& jt = js[j];
    const auto pair = std::lower_bound(pairs.begin(), pairs.end(), jt, [](const ContactPair& p, const Joint& q) {
      return p.a < q.block_a || (p.a == q.block_a && p.b < q.block_b);
    });
    if (pair == pairs.end() || pair->a != jt.block_a || pair->b != jt.block_b) continue;
    double tx = blocks_.vx[jt.vertex_b] - blocks_.vx[jt.vertex_a];
    double ty = blocks_.vy[jt.vertex_b] - blocks_.vy[jt.vertex_a];
    const double tl = std::hypot(tx, ty);
    tx /= tl;
    ty /= tl;
    JointForce& out = f[j];
    for (Index m = pair->first; m < pair->last; ++m) {
      const Contact& c = cs[m];
      if (c.joint != j) continue;
      const double ux = blocks_.vx[c.edge1] - blocks_.vx[c.edge0], uy = blocks_.vy[c.edge1] - blocks_.vy[c.edge0];
      const double proj = (ux * tx + uy * ty) / std::hypot(ux, uy);
      out.normal -= c.normal_force;  // compression positive per contact -> tension positive
      // The shear spring pushes the vertex by -shear_force along the edge: on block_a directly
      // when it owns the vertex, as the reaction otherwise.
      out.shear += (c.vblock == jt.block_a ? -1.0 : 1.0) * c.shear_force * proj;
      ++out.contacts;
    }
  }
  return f;
}

std::size_t Engine::fracture_check() {
  auto& js = blocks_.joints;
  if (js.empty()) return 0;
  const std::vector<JointForce> f = joint_forces();
  const auto nj = static_cast<std::int64_t>(js.size());
  std::vector<FailureRatios> ratio(js.size());
  std::vector<char> breaks(js.size(), 0);
  // Judged in parallel against the state of the step; nothing is changed until all are judged.
#pragma omp parallel for schedule(static)
  for (std::int64_t j = 0; j < nj; ++j) {
    const Joint& jt = js[j];
    if (jt.broken || f[j].contacts == 0) continue;
    ratio[j] = failure_ratios(f[j], jt.length, scene_.joint_sets[static_cast<std::size_t>(jt.joint_set)]);
    breaks[j] = ratio[j].broken() ? 1 : 0;
  }
  std::size_t n = 0;
  for (std::size_t j = 0; j < js.size(); ++j) {
    if (!breaks[j]) continue;
    Joint& jt = js[j];
    jt.broken = true;
    jt.failure = ratio[j].type();
    CrackEvent ev;
    ev.t = time_;
    ev.x = 0.5 * (blocks_.vx[jt.vertex_a] + blocks_.vx[jt.vertex_b]);
    ev.y = 0.5 * (blocks_.vy[jt.vertex_a] + blocks_.vy[jt.vertex_b]);
    ev.type = jt.failure;
    ev.joint = static_cast<Index>(j);
    ev.r1 = ratio[j].r1;
    ev.r2 = ratio[j].r2;
    cracks_.push_back(ev);
    ++crack_counts_.total;
    if (ev.type == CrackType::Tensile)
      ++crack_counts_.tensile;
    else
      ++crack_counts_.shear;
    ++n;
  }
  return n;
}

}  // namespace ddafrac::dda
