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

/// A contact whose joint (or tie) held it at the previous step and no longer does: its joint has
/// just broken, and what it stored beyond what its springs start the step with is released.
bool just_broke(const Contact& c, bool bonded_now) { return c.was_bonded && !bonded_now; }
}  // namespace

ContactEnergy contact_energy(const Contact& c) {
  ContactEnergy e;
  if (c.trial == ContactState::Open) return e;
  e.normal = spring_energy(normal_stiffness(c, c.d_iter), c.d_iter - c.rest_gap);
  if (c.trial == ContactState::Locked)
    e.shear = spring_energy(c.ks, c.s_iter);
  else
    e.shear = sliding_shear_energy(friction_limit(c, 1.0), c.ks);
  if (c.damaged_ks > 0.0) {
    e.damaged = damaged_part_slides(c) ? sliding_shear_energy(friction_limit(c, c.damage), c.damaged_ks)
                                       : spring_energy(c.damaged_ks, c.s_iter - c.damaged_slip);
    e.shear += e.damaged;
  }
  return e;
}

StepEnergy released_energy(const Contact& c, bool bonded_now) {
  StepEnergy e;
  (just_broke(c, bonded_now) ? e.joint_breaks : e.numerical) += c.stored_normal + c.stored_shear;
  return e;
}

namespace {
/// An ordinary contact that closes from a gap (d0 above its rest gap) only pushes from the moment
/// it touches: the linear system's start energy ½·kn·(d0 − rest gap)² of its spring is fictitious.
bool closes_from_a_gap(const Contact& c, bool bonded_now) {
  const bool carries_tension = bonded_now || (c.cohesive && !c.cohesion_lost);
  return !carries_tension && c.d0 > c.rest_gap;
}

/// What a spring of stiffness ks sliding under the friction load f (N/m) dissipates while it slides
/// by ds (m), J/m: the load does work −f·Δs on the blocks, and what the elastic part of the spring
/// gave up or took on, from `stored` (at the previous step's end) to its energy at the friction
/// limit `limit` now, is part of the same slip.
double slip_dissipation(double f, double ds, double ks, double limit, double stored) {
  return -f * ds - (sliding_shear_energy(limit, ks) - stored);
}
}  // namespace

double contact_start_mismatch(const Contact& c, bool bonded_now) {
  if (c.trial == ContactState::Open) return 0.0;
  double mismatch =
      (closes_from_a_gap(c, bonded_now) ? 0.0 : spring_energy(normal_stiffness(c, c.d0), c.d0 - c.rest_gap)) -
      c.stored_normal;
  if (c.trial != ContactState::Locked) return mismatch;
  // A joint's corner that stays stuck when the joint breaks releases the difference (its joint's
  // damaged part and the rest of its intact part, carried into one spring: contact_step_energy).
  if (!just_broke(c, bonded_now)) mismatch += spring_energy(c.ks, c.s0) - c.stored_shear;
  // A softening joint's damaged part: stuck, its spring re-measured like the intact part's;
  // sliding, booked with its friction (contact_step_energy).
  if (damaged_part_slides(c))
    mismatch += c.stored_damaged;
  else if (c.damaged_ks > 0.0)
    mismatch += spring_energy(c.damaged_ks, c.s0 - c.damaged_slip);
  return mismatch;
}

StepEnergy contact_step_energy(const Contact& c, bool bonded_now) {
  if (c.trial == ContactState::Open) return released_energy(c, bonded_now);
  StepEnergy e;
  const bool broke = just_broke(c, bonded_now);
  // Normal spring along the linearised step: ½·kn·Δd². The fictitious start energy of a contact
  // that closes from a gap is not the scheme's to dissipate.
  const double dd = c.d_iter - c.d0;
  e.numerical += 0.5 * normal_stiffness(c, c.d_iter) * dd * dd;
  if (closes_from_a_gap(c, bonded_now)) e.numerical -= spring_energy(c.kn, c.d0 - c.rest_gap);
  const double ds = c.s_iter - c.s0;
  if (c.trial == ContactState::Locked) {
    e.numerical += 0.5 * c.ks * ds * ds;
    // A corner stuck across its joint's break keeps the joint's spring (brittle: nothing to
    // release) or, for a softening joint that breaks before its damage reaches 1, one spring
    // holding the joint's force (carry_contact_state), ½·D·(1 − D)·ks·s_p² below its two parts.
    if (broke) e.joint_breaks += c.stored_shear - spring_energy(c.ks, c.s0);
    if (damaged_part_slides(c))
      e.friction += slip_dissipation(c.friction_force, ds, c.damaged_ks, friction_limit(c, c.damage), c.stored_damaged);
    else if (c.damaged_ks > 0.0)
      e.numerical += 0.5 * c.damaged_ks * ds * ds;
    return e;
  }
  const double start_shear = sliding_shear_energy(c.friction_force, c.ks);
  e.friction += slip_dissipation(c.friction_force, ds, c.ks, friction_limit(c, 1.0), start_shear);
  (broke ? e.joint_breaks : e.friction) += c.stored_shear - start_shear;
  return e;
}

}  // namespace ddafrac::dda
