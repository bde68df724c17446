// Engine: joint forces and the fracture check of virtual joints after each accepted step
// (docs/design.md §5).
#include "ddafrac/dda/engine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "contact_commit.hpp"
#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/energy_ledger.hpp"
#include "ddafrac/dda/geometry.hpp"
#include "ddafrac/dda/softening.hpp"
#include "deterministic_sum.hpp"

namespace ddafrac::dda {

namespace {

/// The strength of a joint of set `js` and length `length` under the normal force of `f`.
JointStrength strength_under(const JointForce& f, double length, const scene::JointSet& js) {
  const double compression = std::max(0.0, -f.normal);
  return joint_strength(js.tensile_strength, js.cohesion, std::tan(js.friction_angle), length, compression);
}

/// The failure ratios of the forces `f` against a joint's `strength` (failure_ratios).
FailureRatios ratios_against(const JointForce& f, const JointStrength& strength) {
  auto ratio = [](double load, double limit) {
    if (load <= 0.0) return 0.0;
    return limit > 0.0 ? load / limit : std::numeric_limits<double>::infinity();
  };
  FailureRatios r;
  r.r1 = ratio(f.normal, strength.tension);
  r.r2 = ratio(std::abs(f.shear), strength.shear);
  return r;
}

}  // namespace

FailureRatios failure_ratios(const JointForce& f, double length, const scene::JointSet& js) {
  return ratios_against(f, strength_under(f, length, js));
}

JointForce stress_traction(const BlockSystem& blocks, const Joint& j) {
  return stress_traction(
      blocks, j,
      0.5 * (blocks.stress[static_cast<std::size_t>(j.block_a)] + blocks.stress[static_cast<std::size_t>(j.block_b)]));
}

JointForce stress_traction(const BlockSystem& blocks, const Joint& j, const Vec3& s) {
  const meshes::Point t = blocks.joint_tangent(j);
  const double tx = t.x, ty = t.y;
  // Outward from block_a: away from its centroid (its blocks are convex).
  const meshes::Point mid = blocks.joint_midpoint(j);
  const PolygonIntegrals& a = blocks.geometry[static_cast<std::size_t>(j.block_a)];
  const double sign = ty * (mid.x - a.cx) - tx * (mid.y - a.cy) >= 0.0 ? 1.0 : -1.0;
  const double nx = sign * ty, ny = -sign * tx;
  const double fx = (s[0] * nx + s[2] * ny) * j.length, fy = (s[2] * nx + s[1] * ny) * j.length;
  JointForce f;
  f.normal = fx * nx + fy * ny;
  f.shear = fx * tx + fy * ty;
  return f;
}

JointLoadShare joint_load_share(const BlockSystem& blocks, const std::vector<JointForce>& forces) {
  double fn_load = 0.0, load_n2 = 0.0, fs_load = 0.0, load_s2 = 0.0;  // (N/m)²
  JointLoadShare share;
  for (std::size_t j = 0; j < blocks.joints.size(); ++j) {
    const Joint& jt = blocks.joints[j];
    if (!forces[j].judged(jt)) continue;
    const JointForce load = stress_traction(blocks, jt);
    fn_load += forces[j].normal * load.normal;
    load_n2 += load.normal * load.normal;
    fs_load += forces[j].shear * load.shear;
    load_s2 += load.shear * load.shear;
    ++share.joints;
  }
  if (load_n2 > 0.0) share.normal = fn_load / load_n2;
  if (load_s2 > 0.0) share.shear = fs_load / load_s2;
  return share;
}

std::vector<JointForce> Engine::joint_forces() const {
  const auto& js = blocks_.joints;
  const auto& cs = set_.contacts;
  const auto& pairs = set_.pairs;
  std::vector<JointForce> f(js.size());
  const auto np = static_cast<std::int64_t>(pairs.size());
  // A joint's contacts lie in the contact range of its block pair: each pair sums its joints'
  // contacts in list order, so no two threads add to one joint and the sums are the same for any
  // thread count. (Walking the pairs, not the joints, spares a search for each joint's pair.)
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < np; ++p) {
    Index joint = -1;
    double tx = 0.0, ty = 0.0;  // unit tangent of that joint, from its vertex_a to its vertex_b
    for (Index m = pairs[p].first; m < pairs[p].last; ++m) {
      const Contact& c = cs[m];
      if (c.joint < 0) continue;
      const Joint& jt = js[static_cast<std::size_t>(c.joint)];
      if (c.joint != joint) {
        joint = c.joint;
        const meshes::Point t = blocks_.joint_tangent(jt);
        tx = t.x;
        ty = t.y;
      }
      const double ux = blocks_.vx[c.edge1] - blocks_.vx[c.edge0], uy = blocks_.vy[c.edge1] - blocks_.vy[c.edge0];
      const double proj = (ux * tx + uy * ty) / std::hypot(ux, uy);
      JointForce& out = f[static_cast<std::size_t>(c.joint)];
      out.normal -= c.normal_force;  // compression positive per contact -> tension positive
      // A softening joint's spring carries tension with (1 − D) of its stiffness.
      out.normal_undamaged -=
          c.damage > 0.0 && c.normal_force < 0.0 ? c.normal_force / (1.0 - c.damage) : c.normal_force;
      // The shear spring pushes the vertex by -shear_force along the edge: on block_a directly
      // when it owns the vertex, as the reaction otherwise.
      const double towards_a = c.vblock == jt.block_a ? -1.0 : 1.0;
      out.shear += towards_a * c.shear_force * proj;
      // (1 − D)·ks·s + D·ks·(s − s_p) = ks·s − D·ks·s_p: the undamaged spring's force is ks·s.
      out.shear_undamaged += towards_a * (c.shear_force + c.damaged_ks * c.damaged_slip) * proj;
      ++out.contacts;
    }
  }
  return f;
}

std::vector<JointForce> Engine::fracture_loads(std::vector<JointForce> f) const {
  if (scene_.analysis.fracture_load != scene::FractureLoad::BlockStress) return f;
  const auto& js = blocks_.joints;
  const auto nj = static_cast<std::int64_t>(js.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t j = 0; j < nj; ++j) {
    if (!f[j].judged(js[j])) continue;
    const int contacts = f[j].contacts;
    f[j] = stress_neighbourhoods_.blocks.empty()
               ? stress_traction(blocks_, js[j])
               : stress_traction(blocks_, js[j], neighbourhood_stress(blocks_, stress_neighbourhoods_, j));
    f[j].contacts = contacts;
  }
  return f;
}

std::vector<FailureRatios> Engine::joint_ratios(const std::vector<JointForce>& f) const {
  const auto& js = blocks_.joints;
  const auto nj = static_cast<std::int64_t>(js.size());
  std::vector<FailureRatios> ratio(js.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t j = 0; j < nj; ++j) {
    const Joint& jt = js[j];
    if (!f[j].judged(jt)) continue;
    ratio[j] = failure_ratios(f[j], jt.length, scene_.joint_sets[static_cast<std::size_t>(jt.joint_set)]);
  }
  return ratio;
}

std::vector<double> Engine::joint_utilisation() const {
  std::vector<double> u(blocks_.block_count(), kNoVirtualJoints);
  const std::vector<FailureRatios> ratio = joint_ratios(fracture_loads(joint_forces()));
  for (std::size_t j = 0; j < ratio.size(); ++j) {
    const double r = ratio[j].largest();  // 0 for a broken joint: its blocks had joints
    const Joint& jt = blocks_.joints[j];
    u[static_cast<std::size_t>(jt.block_a)] = std::max(u[static_cast<std::size_t>(jt.block_a)], r);
    u[static_cast<std::size_t>(jt.block_b)] = std::max(u[static_cast<std::size_t>(jt.block_b)], r);
  }
  return u;
}

namespace {

/// Damage of a joint that does not soften (its set has no fracture energy, or it is not judged).
constexpr double kDoesNotSoften = -1.0;

/// A softening joint's damage after this step, and the mode that drives it.
struct Softened {
  double damage = kDoesNotSoften;
  CrackType mode = CrackType::Tensile;
};

/// The damage of a softening joint with the forces `f` its springs carry now, judged on the
/// ratios they would carry undamaged (returned in `ratio`). With the modes combined
/// (ModeInteraction::Quadratic), on the drive √(r1² + r2²) and the mix of the two modes'
/// ductilities. Otherwise each mode on its own law where the set gives shear its own fracture
/// energy (the larger damage wins), else the larger ratio on the tension's law.
Softened soften(const Joint& jt, const JointForce& f, const scene::JointSet& set, FailureRatios& ratio) {
  JointForce undamaged = f;
  undamaged.normal = f.normal_undamaged;
  undamaged.shear = f.shear_undamaged;
  const JointStrength strength = strength_under(undamaged, jt.length, set);
  ratio = ratios_against(undamaged, strength);
  const double tensile_ductility =
      softening_ductility(set.fracture_energy, set.tensile_strength, f.contacts * set.normal_stiffness, jt.length);
  // μ of shear from its strength under the joint's compression (Pa) and its shear springs; the
  // tension's without a shear fracture energy of its own.
  const double shear_strength = strength.shear / jt.length;
  const double shear_ductility =
      set.shear_fracture_energy
          ? softening_ductility(*set.shear_fracture_energy, shear_strength, f.contacts * set.shear_stiffness, jt.length)
          : tensile_ductility;
  if (set.mode_interaction == scene::ModeInteraction::Quadratic) {
    const double drive = std::hypot(ratio.r1, ratio.r2);
    const double ductility = mixed_mode_ductility(ratio.r1, ratio.r2, tensile_ductility, shear_ductility);
    return {std::max(jt.damage, softening_damage(drive, ductility)), ratio.type()};
  }
  if (!set.shear_fracture_energy)
    return {std::max(jt.damage, softening_damage(ratio.largest(), tensile_ductility)), ratio.type()};
  const double tensile = softening_damage(ratio.r1, tensile_ductility);
  const double shear = softening_damage(ratio.r2, shear_ductility);
  const CrackType mode = tensile == shear ? ratio.type() : (tensile > shear ? CrackType::Tensile : CrackType::Shear);
  return {std::max({jt.damage, tensile, shear}), mode};
}

/// Per joint, its damage after this step if its set softens (JointSet::softens), whose ratios
/// replace its entry of `ratio` (soften); kDoesNotSoften for every other joint. Empty if no joint
/// set softens. Each joint its own.
std::vector<Softened> softened_damage(const BlockSystem& blocks, const scene::Scene& scene,
                                      const std::vector<JointForce>& f, std::vector<FailureRatios>& ratio) {
  const auto& sets = scene.joint_sets;
  if (std::none_of(sets.begin(), sets.end(), [](const scene::JointSet& s) { return s.softens(); })) return {};
  const auto& js = blocks.joints;
  std::vector<Softened> damage(js.size());
  const auto nj = static_cast<std::int64_t>(js.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t j = 0; j < nj; ++j) {
    const Joint& jt = js[j];
    const scene::JointSet& set = sets[static_cast<std::size_t>(jt.joint_set)];
    if (f[j].judged(jt) && set.softens()) damage[j] = soften(jt, f[j], set, ratio[j]);
  }
  return damage;
}

}  // namespace

std::size_t Engine::fracture_check() {
  auto& js = blocks_.joints;
  if (js.empty()) return 0;
  // Judged against the state of the step; nothing is changed until all are judged.
  const std::vector<JointForce> forces = joint_forces();
  std::vector<FailureRatios> ratio = joint_ratios(fracture_loads(forces));
  const std::vector<Softened> damage = softened_damage(blocks_, scene_, forces, ratio);
  std::size_t n = 0;
  bool softened = false;
  for (std::size_t j = 0; j < js.size(); ++j) {
    Joint& jt = js[j];
    const bool softens = !damage.empty() && damage[j].damage != kDoesNotSoften;
    if (softens && damage[j].damage < 1.0) {
      softened = softened || damage[j].damage > jt.damage;
      jt.damage = damage[j].damage;
      continue;
    }
    if (!softens && !ratio[j].broken()) continue;
    jt.broken = true;
    jt.failure = softens ? damage[j].mode : ratio[j].type();
    CrackEvent ev;
    ev.t = time_;
    const meshes::Point mid = blocks_.joint_midpoint(jt);
    ev.x = mid.x;
    ev.y = mid.y;
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
  if (softened) ledger_.total.joint_breaks += follow_joint_damage();
  return n;
}

double Engine::follow_joint_damage() {
  const auto& js = blocks_.joints;
  const ContactProperties properties(scene_);
  return detail::chunked_sum<double>(static_cast<std::int64_t>(set_.contacts.size()), [&](std::int64_t k) {
    Contact& c = set_.contacts[k];
    if (!c.bonded(js) || js[static_cast<std::size_t>(c.joint)].damage == c.damage) return 0.0;
    const double before = c.stored_normal + c.stored_shear;
    properties.assign(c, blocks_);  // the joint's damage and the weakened shear spring
    // Committed again at the step's end state with the weakened springs (a bonded contact is locked).
    c.fn_iter = -normal_stiffness(c, c.d_iter) * (c.d_iter - c.rest_gap);
    settle_damaged_part(c);
    return before - detail::commit_and_store(c).total();
  });
}

}  // namespace ddafrac::dda
