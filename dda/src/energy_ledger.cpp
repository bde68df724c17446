#include "ddafrac/dda/energy_ledger.hpp"

#include <algorithm>
#include <cmath>

namespace ddafrac::dda {

StepEnergy& StepEnergy::operator+=(const StepEnergy& o) {
  work_gravity += o.work_gravity;
  work_loads += o.work_loads;
  work_supports += o.work_supports;
  friction += o.friction;
  joint_breaks += o.joint_breaks;
  numerical += o.numerical;
  return *this;
}

double EnergyLedger::scale() const {
  const double supplied = initial + work();
  return supplied > 0.0 ? supplied : std::max(stored.stored(), dissipated());
}

double EnergyLedger::balance_error() const {
  const double s = scale();
  return s > 0.0 ? residual() / s : 0.0;
}

namespace {
/// Elastic part of a sliding contact's shear spring at the friction limit f: ½·f²/ks.
double sliding_shear_energy(double friction, double ks) { return ks > 0.0 ? 0.5 * friction * friction / ks : 0.0; }
}  // namespace

ContactEnergy contact_energy(const Contact& c) {
  ContactEnergy e;
  if (c.trial == ContactState::Open) return e;
  e.normal = spring_energy(c.kn, c.d_iter);
  if (c.trial == ContactState::Locked)
    e.shear = spring_energy(c.ks, c.s_iter);
  else
    e.shear = sliding_shear_energy(c.tan_phi * std::max(c.fn_iter, 0.0), c.ks);
  return e;
}

StepEnergy released_energy(const Contact& c, bool bonded_now) {
  StepEnergy e;
  (c.was_bonded && !bonded_now ? e.joint_breaks : e.numerical) += c.stored_normal + c.stored_shear;
  return e;
}

StepEnergy contact_step_energy(const Contact& c, bool bonded_now) {
  if (c.trial == ContactState::Open) return released_energy(c, bonded_now);
  StepEnergy e;
  const bool broke = c.was_bonded && !bonded_now;
  // Normal spring along the linearised step: ½·kn·Δd². An ordinary contact that closes from a
  // gap d0 > 0 only pushes from the moment it touches, so the spring's fictitious start energy
  // ½·kn·d0² is not the scheme's to dissipate.
  const double dd = c.d_iter - c.d0;
  e.numerical += 0.5 * c.kn * dd * dd;
  const bool carries_tension = bonded_now || (c.cohesive && !c.cohesion_lost);
  if (!carries_tension && c.d0 > 0.0) e.numerical -= 0.5 * c.kn * c.d0 * c.d0;
  if (c.trial == ContactState::Locked) {
    const double ds = c.s_iter - c.s0;
    e.numerical += 0.5 * c.ks * ds * ds;
    return e;
  }
  // Sliding: the friction load does work −f·Δs on the blocks; what the elastic part of the
  // shear spring gave up or took on since the previous step is part of the same slip.
  const double start_shear = sliding_shear_energy(c.friction_force, c.ks);
  const double end_shear = contact_energy(c).shear;
  e.friction = -c.friction_force * (c.s_iter - c.s0) - (end_shear - start_shear);
  (broke ? e.joint_breaks : e.friction) += c.stored_shear - start_shear;
  return e;
}

}  // namespace ddafrac::dda
