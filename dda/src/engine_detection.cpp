// Engine: the contact list of each step (detection, the state carried from the previous step,
// properties and linearisation), and the trial states the open-close iteration starts from
// (docs/design.md §4).
#include <algorithm>
#include <cmath>

#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/energy_ledger.hpp"
#include "ddafrac/dda/engine.hpp"
#include "deterministic_sum.hpp"

namespace ddafrac::dda {

namespace {
using detail::chunked_sum;

/// What the contacts that vanished at a detection add up to (Engine::detect).
struct VanishedContacts {
  StepEnergy released;
  long ties_lost = 0;
  VanishedContacts& operator+=(const VanishedContacts& o) {
    released += o.released;
    ties_lost += o.ties_lost;
    return *this;
  }
};
}  // namespace

void Engine::detect() {
  std::vector<Contact>& found = spare_contacts_;         // the list of the step before last: storage reused
  const std::vector<Contact>& previous = set_.contacts;  // the previous step's list, until the swap below
  detect_contacts(blocks_, options_.detection, detection_, previous, found);
  stats_.pair_list_builds = detection_.pair_list_builds;
  const ContactProperties properties(scene_);
  std::vector<std::uint8_t> carried(previous.size(), 0);  // per previous contact: carried on or vanished
  const auto nc = static_cast<std::int64_t>(found.size());
  saved_slide_sign_.resize(found.size());
  linear_.resize(found.size());
  const bool first = step_ == 0;
  const bool ties = scene_.analysis.intact_nodes == scene::IntactNodes::Tie;
  const NodeTieGroups tie_groups = ties ? node_tie_groups(blocks_) : NodeTieGroups{};
  long missed = 0, cohesive = 0, overlapping = 0;
  double deepest = 0.0, deepest_overlap = 0.0;
  const double deep_energy = kDeepContactEnergyFraction * ledger_.scale();  // J/m
  // One pass over the new records (each is read and written once per step, not once per task).
#pragma omp parallel for schedule(static) reduction(+ : missed, cohesive, overlapping) \
    reduction(max : deepest, deepest_overlap)
  for (std::int64_t k = 0; k < nc; ++k) {
    Contact& c = found[k];
    const double tie_end = ties && c.shared_node ? node_copy_on_edge(c, blocks_) : -1.0;
    c.tied = tie_end >= 0.0 && tie_groups.tied(c.vertex, tie_end == 0.0 ? c.edge0 : c.edge1);
    const Index tie_set = c.tied ? tie_groups.joint_set[static_cast<std::size_t>(c.vertex)] : kNodeNotTied;
    const CarriedState from =
        carry_contact_state(previous, detection_.previous_by_vertex, found, c, blocks_.joints, blocks_);
    const Contact* p = from.previous;
    if (p) {
#pragma omp atomic write
      carried[static_cast<std::size_t>(p - previous.data())] = 1;
    }
    properties.assign(c, blocks_, tie_set);
    if (c.tied) c.ref_t = tie_end;  // the other copy, on whichever line holds it
    const bool spring_kept = from.swapped_at_break && keep_normal_spring(c, *p);
    const bool held = c.held(blocks_.joints);
    if (held) c.state = ContactState::Locked;
    if (first && !held && c.state != ContactState::Open) start_cohesive(c);
    if (c.cohesive) ++cohesive;
    // A contact seen for the first time after step 1 already deeper than one step's allowed
    // displacement, or taking a new line whose spring takes a share of the balance at once,
    // closed unseen (Statistics::missed_contacts). On the line it had, the spring's energy
    // changes only by the linearisation's error. A released tie's contact was held all along.
    const double overlap = std::max(-c.d0, 0.0);
    const bool new_line = !p || p->vertex != c.vertex || p->edge0 != c.edge0;
    c.same_line = !new_line;
    const double taken = spring_kept ? 0.0 : spring_energy(c.kn, overlap) - (p ? p->stored_normal : 0.0);  // J/m
    if (!first && !from.tie_released && ((!p && overlap > allowed_) || (new_line && taken > deep_energy))) {
      ++missed;
      deepest = std::max(deepest, overlap);
    }
    // At t = 0 no two blocks may overlap by more than one step's allowed displacement: deeper,
    // the mesh's cells or bodies interpenetrate (Statistics::initial_overlaps).
    if (first && !held && -c.d0 > allowed_) {
      ++overlapping;
      deepest_overlap = std::max(deepest_overlap, -c.d0);
    }
    linearise_contact(c, linear_[k], blocks_);
    // An ordinary contact that starts the step open, or is new, pushes from the overlap it has
    // now as far as that lies inside the open-close band; overlap deeper than the band (a contact
    // found late) still pushes back (Contact::rest_gap). The contact of a node whose tie was just
    // released pushes from all the overlap the tie held (what the tie stored went with it to the
    // break; a tie compressed by its share of a flat's load holds micrometres), and while it stays
    // open from what is left of that overlap.
    if (!p || c.state == ContactState::Open) {
      const double deepest_rest = std::min(-state_band(), from.tie_released ? c.d0 : p ? p->rest_gap : 0.0);
      c.rest_gap = held || c.cohesive ? 0.0 : std::clamp(c.d0, deepest_rest, 0.0);
    }
    saved_slide_sign_[k] = c.slide_sign;
  }
  // One pass over the vanished contacts: what they stored, and the ties among them that their
  // node's joints still held (Statistics::ties_lost).
  const VanishedContacts vanished_sum =
      chunked_sum<VanishedContacts>(static_cast<std::int64_t>(carried.size()), [&](std::int64_t k) {
        const Contact& vanished = previous[k];
        if (carried[k]) return VanishedContacts{};
        // A vanished tie is released (never bonded to a joint): what it stored goes to joint breaks.
        VanishedContacts one{released_energy(vanished, vanished.bonded(blocks_.joints)), 0};
        if (vanished.tied && tie_groups.tied(vanished.vertex, vanished.ref_t == 0.0 ? vanished.edge0 : vanished.edge1))
          one.ties_lost = 1;
        return one;
      });
  ledger_.total += vanished_sum.released;
  stats_.ties_lost += vanished_sum.ties_lost;
  std::swap(set_.contacts, found);
  build_contact_topology(set_, blocks_.block_count());
  if (nc > 0) active_.contacts = true;
  if (first) active_.cohesion = cohesive > 0;
  stats_.missed_contacts += missed;
  stats_.deepest_missed = std::max(stats_.deepest_missed, deepest);
  if (first) {
    stats_.initial_overlaps = overlapping;
    stats_.deepest_initial_overlap = deepest_overlap;
  }
}

void Engine::start_cohesive(Contact& c) const {
  // Real joints closed at t = 0 are the pre-existing joints of the rock mass; contacts made
  // later (impacts, re-closing cracks) and broken virtual joints never get cohesion.
  if (c.shared_node || (c.cohesion <= 0.0 && c.tensile_strength <= 0.0)) return;
  c.cohesive_length = cohesive_length(c, blocks_, options_.detection.angle_tolerance);
  c.cohesive = c.cohesive_length > 0.0;
}

void Engine::reset_trials() {
  const auto nc = static_cast<std::int64_t>(set_.contacts.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t k = 0; k < nc; ++k) {
    Contact& c = set_.contacts[k];
    c.trial = c.state;
    c.damaged_trial = c.damaged_state;
    c.fn_iter = c.normal_force;
    c.slide_sign = saved_slide_sign_[k];
    c.cohesion_lost = false;
  }
}

}  // namespace ddafrac::dda
