#include "ddafrac/dda/contact_mechanics.hpp"

#include <cmath>

#include "ddafrac/dda/geometry.hpp"

namespace ddafrac::dda {

ContactProperties::ContactProperties(const scene::Scene& scene) : scene_(scene) {
  for (const scene::JointSet& js : scene.joint_sets) tan_phi_.push_back(std::tan(js.friction_angle));
}

void ContactProperties::assign(Contact& c, const BlockSystem& blocks, Index tie_set) const {
  const bool bonded = c.bonded(blocks.joints);
  const Index set = bonded   ? blocks.joints[static_cast<std::size_t>(c.joint)].joint_set
                    : c.tied ? tie_set
                             : static_cast<Index>(scene_.real_joints);
  c.joint_set = set;
  const scene::JointSet& js = scene_.joint_sets[static_cast<std::size_t>(set)];
  c.damage = bonded ? blocks.joints[static_cast<std::size_t>(c.joint)].damage : 0.0;
  c.kn = js.normal_stiffness;
  c.ks = (1.0 - c.damage) * js.shear_stiffness;
  c.damaged_ks = c.damage * js.shear_stiffness;
  c.tan_phi = tan_phi_[static_cast<std::size_t>(set)];
  c.cohesion = js.cohesion;
  c.tensile_strength = js.tensile_strength;
  // Two corners meeting at a shared mesh node have no face for friction to act along (the
  // reference line is one of four edges picked by the angle rules): the contact only keeps
  // them from overlapping (docs/design.md §4.6).
  // Frictionless means no shear spring either: with ks > 0 and tanφ = 0 the contact would
  // flip between locked and sliding at every open-close iteration.
  if (c.shared_node) c.tan_phi = c.ks = 0.0;
  // A tie's energy must not depend on which line of the corner the detection chose: equal normal
  // and shear springs make it ½·kn·|x_v − x_u|² whatever the line's direction.
  if (c.tied) c.ks = c.kn;
}

double node_copy_on_edge(const Contact& c, const BlockSystem& blocks) {
  const meshes::Index node = blocks.vertex_node[static_cast<std::size_t>(c.vertex)];
  if (blocks.vertex_node[static_cast<std::size_t>(c.edge0)] == node) return 0.0;
  if (blocks.vertex_node[static_cast<std::size_t>(c.edge1)] == node) return 1.0;
  return -1.0;
}

double cohesive_length(const Contact& c, const BlockSystem& s, double angle_tolerance) {
  const double x2 = s.vx[c.edge0], y2 = s.vy[c.edge0];
  const double dx = s.vx[c.edge1] - x2, dy = s.vy[c.edge1] - y2;
  const double l2 = dx * dx + dy * dy;
  const double l = std::sqrt(l2);
  const auto b = static_cast<std::size_t>(c.vblock);
  const Index first = s.begin(b), last = s.end(b);
  const Index previous = c.vertex == first ? last - 1 : c.vertex - 1;
  const Index next = c.vertex + 1 == last ? first : c.vertex + 1;
  double overlap = 0.0;
  for (const Index other : {previous, next}) {
    const double ex = s.vx[other] - s.vx[c.vertex], ey = s.vy[other] - s.vy[c.vertex];
    const double le = std::hypot(ex, ey);
    // The faces of two CCW blocks in contact run in opposite directions; the vertex's edge
    // bonds only if it lies along the reference edge (a corner on a face has no face to bond).
    const double sine = std::abs(ex * dy - ey * dx) / (le * l);
    if (le == 0.0 || sine > std::sin(angle_tolerance)) continue;
    const double ta = ((s.vx[c.vertex] - x2) * dx + (s.vy[c.vertex] - y2) * dy) / l2;
    const double tb = ((s.vx[other] - x2) * dx + (s.vy[other] - y2) * dy) / l2;
    const double along = std::min(1.0, std::max(ta, tb)) - std::max(0.0, std::min(ta, tb));
    overlap = std::max(overlap, along * l);
  }
  return 0.5 * overlap;
}

double normal_gap(double x1, double y1, double x2, double y2, double x3, double y3) {
  const double l = std::hypot(x3 - x2, y3 - y2);
  return ((x3 - x2) * (y2 - y1) - (y3 - y2) * (x2 - x1)) / l;
}

void linearise_contact(Contact& c, ContactLinearisation& lin, const BlockSystem& s) {
  const double x1 = s.vx[c.vertex], y1 = s.vy[c.vertex];
  const double x2 = s.vx[c.edge0], y2 = s.vy[c.edge0];
  const double x3 = s.vx[c.edge1], y3 = s.vy[c.edge1];
  const double dx = x3 - x2, dy = y3 - y2;
  const double l2 = dx * dx + dy * dy;
  const double l = std::sqrt(l2);
  const double ux = dx / l, uy = dy / l;
  c.edge_length = l;
  c.d0 = (dx * (y2 - y1) - dy * (x2 - x1)) / l;
  const double t_now = ((x1 - x2) * dx + (y1 - y2) * dy) / l2;
  if (c.state == ContactState::Open) c.ref_t = t_now;
  c.s0 = (t_now - c.ref_t) * l;
  const PolygonIntegrals& gi = s.geometry[c.vblock];
  const PolygonIntegrals& gj = s.geometry[c.eblock];
  const Mat26 ti = displacement_matrix(gi.cx, gi.cy, x1, y1);
  const Mat26 t2 = displacement_matrix(gj.cx, gj.cy, x2, y2);
  const Mat26 t3 = displacement_matrix(gj.cx, gj.cy, x3, y3);
  lin.e = ((y3 - y2) * ti.row(0) + (x2 - x3) * ti.row(1)).transpose() / l;
  lin.g =
      ((y1 - y3) * t2.row(0) + (x3 - x1) * t2.row(1) + (y2 - y1) * t3.row(0) + (x1 - x2) * t3.row(1)).transpose() / l;
  // d = N / l: the edge length also varies, ∂l = u·(∂P3 − ∂P2), giving −(d0/l)·∂l.
  lin.g -= (c.d0 / l) * (ux * (t3.row(0) - t2.row(0)) + uy * (t3.row(1) - t2.row(1))).transpose();
  lin.es = (ux * ti.row(0) + uy * ti.row(1)).transpose();
  const double w2 = 1.0 - c.ref_t, w3 = c.ref_t;
  lin.gs = -(ux * (w2 * t2.row(0) + w3 * t3.row(0)) + uy * (w2 * t2.row(1) + w3 * t3.row(1))).transpose();
  c.trial = c.state;
  c.damaged_trial = c.damaged_state;
  c.fn_iter = c.normal_force;
  c.d_iter = c.d0;
  c.s_iter = c.s0;
}

double friction_limit(const Contact& c, double share) { return share * c.tan_phi * std::max(c.fn_iter, 0.0); }

namespace {
/// The friction load on a spring sliding in the direction slide_sign at friction_limit(c, share), N/m.
double friction_load(const Contact& c, double share) { return -c.slide_sign * friction_limit(c, share); }
}  // namespace

bool damaged_part_slides(const Contact& c) { return c.damaged_ks > 0.0 && c.damaged_trial == ContactState::Sliding; }

ContactCoefficients contact_coefficients(const Contact& c) {
  ContactCoefficients k;
  switch (c.trial) {
    case ContactState::Open: break;
    case ContactState::Locked:
      // The side of a softening joint's spring (tension or compression) the latest solve found.
      k.kn_eff = normal_stiffness(c, c.d_iter);
      k.ks_eff = c.ks;
      k.fn_rhs = -k.kn_eff * (c.d0 - c.rest_gap);
      k.fs_rhs = -c.ks * c.s0;
      if (damaged_part_slides(c)) {
        k.fs_rhs += friction_load(c, c.damage);
      } else if (c.damaged_ks > 0.0) {
        k.ks_eff += c.damaged_ks;
        k.fs_rhs -= c.damaged_ks * (c.s0 - c.damaged_slip);
      }
      break;
    case ContactState::Sliding:
      k.kn_eff = c.kn;
      k.fn_rhs = -c.kn * (c.d0 - c.rest_gap);
      k.fs_rhs = friction_load(c, 1.0);
      break;
  }
  return k;
}

namespace {

/// The return mapping of a shear spring of stiffness ks (N/m) stretched by s (m) from its
/// reference point, whose force is limited by friction to `limit` (N/m), from the trial state
/// `trial`: it slides while the spring would carry more than the limit, in the direction of s
/// (set in slide_sign), and a sliding one locks once its force in the sliding direction falls
/// below the limit; `tol` (m) is the hysteresis band of judge_contact. Judging a sliding spring by
/// the direction of its step increment instead would lock a contact whose carried shear exceeds
/// a shrinking limit (fn falling) while it unloads slightly, and the locked solution would send
/// it back to sliding.
ContactState judge_slip(ContactState trial, double ks, double s, double limit, double tol, double& slide_sign) {
  if (trial == ContactState::Sliding)
    return ks * s * slide_sign < limit - ks * tol ? ContactState::Locked : ContactState::Sliding;
  if (std::abs(ks * s) > limit + ks * tol) {
    slide_sign = s >= 0.0 ? 1.0 : -1.0;
    return ContactState::Sliding;
  }
  return ContactState::Locked;
}

/// Open or closed with Mohr-Coulomb friction (no cohesion): the state of an ordinary contact
/// with gap d and shear s; fn receives its normal force (compression positive).
ContactState judge_frictional(Contact& c, double d, double s, double tol, double& fn) {
  // A closed contact whose spring would pull (d > rest gap) opens: an ordinary contact carries
  // no tension. The hysteresis band sits on the closing side: an open contact closes only once
  // it overlaps by more than tol, and its spring pushes from the overlap it started the step
  // with (Contact::rest_gap), so the band adds no energy. One whose rest gap lies deeper than the
  // band (a released tie's node contact), or lies above zero gap (a broken joint's corner that kept its
  // compression, keep_normal_spring), closes once it passes its rest gap by tol.
  const double closing = c.rest_gap < -tol || c.rest_gap > 0.0 ? c.rest_gap - tol : -tol;
  if (d > (c.trial == ContactState::Open ? closing : c.rest_gap)) {
    fn = 0.0;
    return ContactState::Open;
  }
  fn = std::max(0.0, -c.kn * (d - c.rest_gap));
  // Elastic predictor (return mapping) on the shear spring measured from the reference point.
  return judge_slip(c.trial, c.ks, s, c.tan_phi * fn, tol, c.slide_sign);
}

/// The damaged part of a bonded softening joint's contact (Contact::damaged_ks) with shear s and
/// normal force fn (compression positive), judged as judge_slip judges a frictional contact on
/// D of its friction limit; in tension it slides with no load, in the direction of its stretch
/// (so that, closing again, it keeps sliding the way it went rather than lock at once and flip
/// the iteration between the two sides of its normal spring). Returns whether its state changed.
bool judge_damaged_part(Contact& c, double s, double fn, double tol) {
  const double limit = c.damage * c.tan_phi * std::max(fn, 0.0);
  const double stretch = s - c.damaged_slip;  // m
  ContactState next = ContactState::Sliding;
  if (limit > 0.0)
    next = judge_slip(c.damaged_trial, c.damaged_ks, stretch, limit, tol, c.slide_sign);
  else
    c.slide_sign = stretch >= 0.0 ? 1.0 : -1.0;
  const bool changed = next != c.damaged_trial;
  c.damaged_trial = next;
  return changed;
}

/// An intact cohesive joint holds (stays locked) while its tension and shear stay within its
/// strength over l_c (joint_strength).
bool cohesion_holds(const Contact& c, double fn, double s) {
  const JointStrength limit =
      joint_strength(c.tensile_strength, c.cohesion, c.tan_phi, c.cohesive_length, std::max(fn, 0.0));
  return -fn <= limit.tension && std::abs(c.ks * s) <= limit.shear;
}

}  // namespace

bool judge_contact(Contact& c, const ContactLinearisation& lin, const Vec6& dv, const Vec6& de, bool bonded,
                   double tol) {
  c.friction_force = c.trial == ContactState::Sliding ? contact_coefficients(c).fs_rhs
                     : damaged_part_slides(c)         ? friction_load(c, c.damage)
                                                      : 0.0;
  const double d = c.d0 + lin.e.dot(dv) + lin.g.dot(de);
  const double s = c.s0 + lin.es.dot(dv) + lin.gs.dot(de);
  ContactState next = ContactState::Locked;
  double fn = -normal_stiffness(c, d) * (d - c.rest_gap);
  // A softening joint's spring that crossed between tension and compression needs another solve
  // with the stiffness of its new side.
  const bool side_changed = c.damage > 0.0 && (d > c.rest_gap) != (c.d_iter > c.rest_gap);
  bool damaged_part_changed = false;
  if (bonded && c.damaged_ks > 0.0) damaged_part_changed = judge_damaged_part(c, s, fn, tol);
  if (!bonded) {
    // A cohesive joint that fails stays failed for the rest of the step's iterations (and for
    // good once the step is accepted): the iteration then cannot cycle on its strength.
    if (c.cohesive && !c.cohesion_lost && !cohesion_holds(c, fn, s)) c.cohesion_lost = true;
    if (!c.cohesive || c.cohesion_lost) next = judge_frictional(c, d, s, tol, fn);
  }
  const bool changed = next != c.trial || side_changed || damaged_part_changed;
  c.trial = next;
  c.fn_iter = fn;
  c.d_iter = d;
  c.s_iter = s;
  return changed;
}

namespace {
/// Commits the damaged part of a bonded softening joint's contact (Contact::damaged_ks) and
/// returns its shear force, N/m: a stuck part's spring force, a sliding part's friction, whose
/// plastic slip keeps the elastic part of its spring at that force.
double commit_damaged_part(Contact& c) {
  if (c.damaged_ks <= 0.0) return 0.0;
  if (c.damaged_trial == ContactState::Sliding) {
    const double force = c.slide_sign * friction_limit(c, c.damage);
    c.damaged_slip = c.s_iter - force / c.damaged_ks;
    return force;
  }
  return c.damaged_ks * (c.s_iter - c.damaged_slip);
}
}  // namespace

void settle_damaged_part(Contact& c) {
  if (c.damaged_ks <= 0.0 || c.damaged_trial == ContactState::Sliding) return;
  const double force = c.damaged_ks * (c.s_iter - c.damaged_slip);
  if (std::abs(force) <= friction_limit(c, c.damage)) return;
  c.damaged_trial = ContactState::Sliding;
  c.slide_sign = force >= 0.0 ? 1.0 : -1.0;
}

void commit_contact(Contact& c) {
  c.state = c.trial;
  c.damaged_state = c.damaged_trial;
  if (c.cohesion_lost) c.cohesive = false;
  c.cohesion_lost = false;
  c.normal_force = c.fn_iter;
  switch (c.state) {
    case ContactState::Open: c.shear_force = 0.0; break;
    case ContactState::Locked: c.shear_force = c.ks * c.s_iter + commit_damaged_part(c); break;
    case ContactState::Sliding: {
      // The spring keeps the elastic part at the friction limit; the rest is plastic slip, by
      // which the reference point moves along the edge.
      const double elastic = c.ks > 0.0 ? c.slide_sign * c.tan_phi * c.fn_iter / c.ks : 0.0;
      c.shear_force = c.ks * elastic;
      c.slip += std::abs(c.s_iter - elastic);
      if (c.edge_length > 0.0) c.ref_t += (c.s_iter - elastic) / c.edge_length;
      break;
    }
  }
}

}  // namespace ddafrac::dda
