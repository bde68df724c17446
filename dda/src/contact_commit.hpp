#pragma once
// Committing a contact at the end of an accepted step. Internal to the DDA library.

#include "ddafrac/dda/contact.hpp"
#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/energy_ledger.hpp"

namespace ddafrac::dda::detail {

/// Commits the contact's converged state (commit_contact) and remembers what its springs store
/// in it (Contact::stored_normal, stored_shear), which the next step's energy is booked against.
/// Returns that energy.
inline ContactEnergy commit_and_store(Contact& c) {
  commit_contact(c);
  const ContactEnergy stored = contact_energy(c);
  c.stored_normal = stored.normal;
  c.stored_shear = stored.shear;
  c.stored_damaged = stored.damaged;
  return stored;
}

}  // namespace ddafrac::dda::detail
