#pragma once
// Contact mechanics: linearised gap and shear, penalty springs, Mohr-Coulomb
// sliding, and the open-close judgement.

#include <vector>

#include "ddafrac/dda/block_system.hpp"
#include "ddafrac/dda/contact.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::dda {

/// Stiffness and friction of contacts from their joint set (bonded joints: their virtual joint
/// set; ties: `tie_set`, the virtual joint set of their node (NodeTieGroups); others,
/// broken joints included: the scene's real joints). kn and ks are the joint set's (the scene
/// parser fills in their defaults, scene/defaults.hpp), but a tie is isotropic (ks = kn) and a
/// shared-node contact frictionless.
class ContactProperties {
 public:
  explicit ContactProperties(const scene::Scene& scene);
  /// Sets c's joint set and properties; reads only c (contacts can be assigned in parallel).
  void assign(Contact& c, const BlockSystem& blocks, Index tie_set = kNodeNotTied) const;

 private:
  const scene::Scene& scene_;
  std::vector<double> tan_phi_;  // per joint set
};

/// l_c of a cohesive contact: half the overlap of the reference edge with the vertex's own edge
/// that lies along it (within `angle_tolerance`, rad). A face bonded along its length has a
/// vertex-edge contact at each end, so the halves add up to the face; a corner touching a face
/// has no face along it and gets 0.
double cohesive_length(const Contact& c, const BlockSystem& blocks, double angle_tolerance);

/// Where the reference edge of a shared-node contact holds the other copy of its node: edge
/// parameter 0 (at edge0) or 1 (at edge1), or -1 if neither end is a copy of the vertex's node (a
/// copy held on its entrance line into the other block, docs/design.md §4.6).
double node_copy_on_edge(const Contact& c, const BlockSystem& blocks);

/// Normal gap, shear displacement from the locked reference point, and their gradients with
/// respect to the unknowns of both blocks, from the current geometry. Open contacts
/// move their reference point to the current projection (s0 = 0). Formulas: docs/design.md §4.2.
void linearise_contact(Contact& c, ContactLinearisation& linear, const BlockSystem& blocks);

/// Exact (nonlinear) normal gap of a vertex against an edge, positive when the vertex is
/// outside the CCW block: d = [(x3-x2)(y2-y1) - (y3-y2)(x2-x1)] / l.
double normal_gap(double x1, double y1, double x2, double y2, double x3, double y3);

/// The normal spring of contact c at gap d (m), N/m: kn, except that a softening joint's spring
/// carries tension (d above the rest gap) with (1 − damage)·kn; a crack closes at full stiffness.
inline double normal_stiffness(const Contact& c, double gap) {
  return gap > c.rest_gap ? (1.0 - c.damage) * c.kn : c.kn;
}

/// A `share` of contact c's friction limit tanφ·f_n, f_n its normal force of the latest solve
/// (compression positive, none in tension): all of it for a sliding contact, D of it for a
/// softening joint's damaged part. N/m.
double friction_limit(const Contact& c, double share);

/// Spring and load coefficients of a contact in its trial state for the assembly:
/// K += kn_eff·[e;g][e;g]^T + ks_eff·[es;gs][es;gs]^T,  F += fn_rhs·[e;g] + fs_rhs·[es;gs]
/// (per state: the table of docs/design.md §4.3).
struct ContactCoefficients {
  double kn_eff = 0.0, ks_eff = 0.0, fn_rhs = 0.0, fs_rhs = 0.0;
};
ContactCoefficients contact_coefficients(const Contact& c);

/// The strength of a joint over a length l (m) under the compressive normal force f_c >= 0
/// (N/m): tension up to σt·l (the tension cut-off) and shear up to c·l + f_c·tanφ
/// (Mohr-Coulomb), both N/m. One law for both joint kinds: the fracture check of the virtual
/// joints (failure_ratios) and the cohesion of the intact real joints (judge_contact).
struct JointStrength {
  double tension = 0.0;  // N/m, largest tensile normal force
  double shear = 0.0;    // N/m, largest shear force
};
inline JointStrength joint_strength(double tensile_strength, double cohesion, double tan_phi, double length,
                                    double compression) {
  return {tensile_strength * length, cohesion * length + compression * tan_phi};
}

/// Judges one contact from the solution of its two blocks; returns true if its state changed.
/// Bonded contacts stay locked (they carry tension; breaking is the fracture check's job); the
/// damaged part of a softening joint's contact sticks or slides on D of the friction limit.
/// Cohesive contacts (intact real joints) stay locked, tension included, while the tension is
/// within σt·l_c and the shear within c·l_c + fn·tanφ; beyond either they lose cohesion and
/// tension for good (commit_contact) and are judged as ordinary frictional contacts.
/// Shear is an elastic-plastic spring measured from the reference point (return mapping): a
/// closed contact slides while ks·|s| exceeds tanφ·fn, in the direction of s; a sliding contact
/// keeps its elastic part at the limit and its reference point follows the plastic slip.
/// A closed ordinary contact opens as soon as its spring would pull (gap > Contact::rest_gap): only
/// bonded and cohesive contacts carry tension.
/// `tolerance` (m) is a hysteresis band that keeps contacts sitting exactly at a threshold from
/// flipping forever: an open contact closes only once it overlaps by more than `tolerance`, a locked one slides only if
/// its shear exceeds the friction limit by ks·tolerance, a sliding one locks only when its
/// shear in the sliding direction falls below the limit by ks·tolerance. (docs/design.md §4.3–§4.5)
bool judge_contact(Contact& c, const ContactLinearisation& linear, const Vec6& d_vertex_block,
                   const Vec6& d_edge_block, bool bonded, double tolerance = 0.0);

/// After the step is accepted: forces, slip and reference point carried to the next step (a
/// sliding contact's reference point moves by its plastic slip, a softening joint's sliding
/// damaged part's plastic slip with it).
void commit_contact(Contact& c);

/// Whether the damaged part of a bonded softening joint's contact (Contact::damaged_ks) slides in
/// the current trial.
bool damaged_part_slides(const Contact& c);

/// After a joint's damage rose (Engine::follow_joint_damage, c's properties assigned anew): its
/// damaged part slides if its spring, measured from its plastic slip, would carry more than its
/// friction at the step's end state; the part that has just started to be damaged has no slip
/// yet. Commit the contact again afterwards.
void settle_damaged_part(Contact& c);

}  // namespace ddafrac::dda
