#pragma once
// The energy ledger of a run (docs/design.md §9): what the blocks store, what the
// loads and supports put in, and where the rest went, so that a run shows whether it created
// energy.
//
// Every accepted step solves one linear system: the inertia of Newmark (γ = 1, β = ½) against
// springs (block elasticity, contacts, anchors) and loads that are linear in the step
// displacement D. For that system the step's energy change is exact:
//
//   ΔK + ΔΠ = W_loads − ½·Dᵀ·K_springs·D,
//
// with ΔΠ the change of the springs' quadratic potentials along the linearised step. The last
// term is the scheme's numerical dissipation (always ≥ 0: the force of every spring is taken at
// the end of the step). What the linearised step does not see shows up as the balance error:
// gaps and areas recomputed on the moved geometry, contacts that appear already overlapping,
// contacts that vanish from the list while loaded.

#include <vector>

#include "ddafrac/dda/block_system.hpp"
#include "ddafrac/dda/contact.hpp"
#include "ddafrac/dda/types.hpp"

namespace ddafrac::dda {

/// Energies stored at one instant, J per unit thickness (J/m).
struct Energies {
  double kinetic = 0.0;       // ½·Vᵀ·M·V of every block
  double kinetic_free = 0.0;  // of the blocks without fixed/prescribed points (platens excluded)
  double strain = 0.0;        // ½·A·σᵀ·C·σ of every block
  double contact = 0.0;       // contact springs (ContactEnergy)
  double support = 0.0;       // anchor springs of fixed and prescribed points, ½·p·|x − target|²
  double stored() const { return kinetic + strain + contact + support; }
  Energies& operator+=(const Energies& o);
};

/// Energy of a spring of stiffness k (N/m per m) stretched or compressed by x (m): ½·k·x², J/m.
inline double spring_energy(double k, double x) { return 0.5 * k * x * x; }

/// Energy a contact's springs store at the end of an accepted step, J/m. Closed contacts:
/// ½·kn·d²; locked ones add ½·ks·s², sliding ones the elastic part of their shear spring at the
/// friction limit, ½·(tanφ·fn)²/ks. The damaged part of a softening joint's shear
/// (Contact::damaged_ks) adds its spring's energy measured from its plastic slip.
struct ContactEnergy {
  double normal = 0.0, shear = 0.0;
  double damaged = 0.0;  // the damaged part's share of `shear`
  double total() const { return normal + shear; }
};
ContactEnergy contact_energy(const Contact& c);

/// Where the energy of one accepted step went, J/m (all cumulative in EnergyLedger).
struct StepEnergy {
  double work_gravity = 0.0;   // body force on the step displacement of the centroids
  double work_loads = 0.0;     // point loads
  double work_supports = 0.0;  // anchor targets moving (prescribed bodies); 0 for fixed ones
  double friction = 0.0;       // dissipated by sliding contacts
  double joint_breaks = 0.0;   // spring energy of broken virtual joints released as they open
  double numerical = 0.0;      // the time scheme's dissipation (see the file comment)
  double damping = 0.0;        // taken out by the mass damping force −η·M·V1 (analysis.mass_damping)
  StepEnergy& operator+=(const StepEnergy& o);
};

/// Where the residual comes from, J/m (cumulative in EnergyLedger). The step's identity holds on
/// the linearised step; between the end of one step (booked on it) and the start of the next
/// (measured on the moved geometry) springs and blocks gain or lose energy that no load put in and
/// no term booked. The five sums add up to residual() to round-off.
struct ResidualSources {
  double contacts_kept = 0.0;  // contacts closed at both ends of the step, on the line they had:
                               // gap and shear re-measured on the moved geometry
  // Contacts on the line they had, open at the step's start and closed at its end: what the
  // overlap built up while the open-close band (EngineOptions::state_tolerance) kept them open
  // stores beyond their rest gap, ½·kn·(d0 − rest gap)² each; zero while the rest gap takes up
  // that overlap (docs/design.md §4.4).
  double contacts_reclosed = 0.0;
  double contacts_new = 0.0;  // contacts new or on a new line that close: their start energy
  double blocks = 0.0;        // strain and kinetic energy on the moved areas and mass matrices
  double supports = 0.0;      // anchor springs at the anchor points moved exactly, not by T·D
  double total() const { return contacts_kept + contacts_reclosed + contacts_new + blocks + supports; }
  ResidualSources& operator+=(const ResidualSources& o);
};

/// Cumulative ledger: initial + work = stored + dissipated, up to the balance error.
struct EnergyLedger {
  double initial = 0.0;  // stored at t = 0
  Energies stored;       // now
  StepEnergy total;      // cumulative since t = 0
  ResidualSources residual_sources;  // cumulative since t = 0: residual() split by where it arose
  double work() const { return total.work_gravity + total.work_loads + total.work_supports; }
  double dissipated() const { return total.friction + total.joint_breaks + total.numerical + total.damping; }
  /// (stored + dissipated) − (initial + work), J/m: positive = energy created.
  double residual() const { return stored.stored() + dissipated() - (initial + work()); }
  /// ((stored + dissipated) − (initial + work)) / (initial + work): positive = energy created.
  /// With nothing to compare against (initial + work ≤ 0) it is relative to the largest of the
  /// stored and dissipated energies.
  double balance_error() const;
  /// What balance_error() divides by, J/m: initial + work, else the larger of stored and
  /// dissipated.
  double scale() const;
  double largest_balance_error = 0.0;  // largest |balance_error()| after any step so far
};

/// |balance error| above which a run warns at its end (1%).
constexpr double kDefaultEnergyBalanceTolerance = 0.01;

/// What the step's linearised contact springs, friction and releases did, from the state of
/// every contact after the converged open-close iteration (trial state, gaps and forces at the
/// step's start and end, energy stored at the end of the previous step). A contact that opens
/// gives up what it stored: to joint_breaks if it was held at the previous step (an intact
/// virtual joint, or a tie) and is not now, else to numerical.
StepEnergy contact_step_energy(const Contact& c, bool bonded_now);

/// What a contact closed at the end of the step stored at its start on the moved geometry (½·kn·d0²,
/// and ½·ks·s0² if it ends locked; nothing for an ordinary contact that closes from a gap) beyond
/// what it was booked with at the end of the previous step, J/m: its share of the residual (0 for a
/// contact that ends open, whose booked energy is released). A sliding contact's shear spring
/// is booked with its friction and adds nothing.
double contact_start_mismatch(const Contact& c, bool bonded_now);

/// What a contact that opens, or vanishes from the contact list, gives up: the energy it stored
/// at the end of the previous step, to joint_breaks if it was held then (an intact virtual joint,
/// or a tie) and is not now (a joint loaded in tension opens wider than the search distance when it breaks),
/// else to numerical.
StepEnergy released_energy(const Contact& c, bool bonded_now);

}  // namespace ddafrac::dda
