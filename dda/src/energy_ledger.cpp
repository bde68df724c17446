#include "ddafrac/dda/energy_ledger.hpp"

#include <algorithm>
#include <cmath>

#include "ddafrac/dda/contact_mechanics.hpp"

namespace ddafrac::dda {

Energies& Energies::operator+=(const Energies& o) {
  kinetic += o.kinetic;
  kinetic_free += o.kinetic_free;
  strain += o.strain;
  contact += o.contact;
  support += o.support;
  return *this;
}

StepEnergy& StepEnergy::operator+=(const StepEnergy& o) {
  work_gravity += o.work_gravity;
  work_loads += o.work_loads;
  work_supports += o.work_supports;
  friction += o.friction;
  joint_breaks += o.joint_breaks;
  numerical += o.numerical;
  damping += o.damping;
  return *this;
}

ResidualSources& ResidualSources::operator+=(const ResidualSources& o) {
  contacts_kept += o.contacts_kept;
  contacts_reclosed += o.contacts_reclosed;
  contacts_new += o.contacts_new;
  blocks += o.blocks;
  supports += o.supports;
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
  e.normal = spring_energy(normal_stiffness(c, c.d_iter), c.d_iter - c.rest_gap);
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

namespace {
/// An ordinary contact that closes from a gap (d0 above its rest gap) only pushes from the moment
/// it touches: the linear system's start energy ½·kn·(d0 − rest gap)² of its spring is fictitious.
bool closes_from_a_gap(const Contact& c, bool bonded_now) {
  const bool carries_tension = bonded_now || (c.cohesive && !c.cohesion_lost);
  return !carries_tension && c.d0 > c.rest_gap;
}
}  // namespace

double contact_start_mismatch(const Contact& c, bool bonded_now) {
  if (c.trial == ContactState::Open) return 0.0;
  double mismatch =
      (closes_from_a_gap(c, bonded_now) ? 0.0 : spring_energy(normal_stiffness(c, c.d0), c.d0 - c.rest_gap)) -
      c.stored_normal;
  if (c.trial == ContactState::Locked) mismatch += spring_energy(c.ks, c.s0) - c.stored_shear;
  return mismatch;
}

StepEnergy contact_step_energy(const Contact& c, bool bonded_now) {
  if (c.trial == ContactState::Open) return released_energy(c, bonded_now);
  StepEnergy e;
  const bool broke = c.was_bonded && !bonded_now;
  // Normal spring along the linearised step: ½·kn·Δd². The fictitious start energy of a contact
  // that closes from a gap is not the scheme's to dissipate.
  const double dd = c.d_iter - c.d0;
  e.numerical += 0.5 * normal_stiffness(c, c.d_iter) * dd * dd;
  if (closes_from_a_gap(c, bonded_now)) e.numerical -= spring_energy(c.kn, c.d0 - c.rest_gap);
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
