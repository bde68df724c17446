// Energy-correct contacts (the energy ledger, contacts that never pull, contacts at shared mesh
// nodes): each case checks a number against a conservation law or an independent reference.
#define BOOST_TEST_MODULE dda_energy
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/dda/synthetic.hpp"
#include "energy_checks.hpp"
#include "fan_scene.hpp"
#include "support.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;
using testing::add_polygon;
using testing::add_rectangle;
using testing::basic_scene;
using testing::body;
using testing::deepest_vertex_inside;
using testing::Fan;

namespace {
constexpr double kG = 9.81;  // m/s²
constexpr double kDegree = common::kRadiansPerDegree;

/// The block's rotation from its first edge (CCW from vertex 0 to vertex 1), radians.
double block_angle(const Engine& e, Index b) {
  const BlockSystem& s = e.blocks();
  const Index v0 = s.begin(static_cast<std::size_t>(b));
  return std::atan2(s.vy[v0 + 1] - s.vy[v0], s.vx[v0 + 1] - s.vx[v0]);
}

// ---------------------------------------------------------------------------------------------
// A square block slides frictionless off the end of a fixed slab and tips over its edge.
struct SlideOff {
  double half = 2.5;          // m, half the block's side
  double density = 17.94;     // kg/m³: a weight of 4.4 kN per metre of thickness
  double kn = 1.5e8;          // N/m
  double speed = 10.0;        // m/s, to +x
  double start_x = -10.0;     // m, block centre at t = 0 (the slab ends at x = 0, top at y = 0)
  double slab_length = 40.0;  // m
  double end_time = 5.0;      // s
};

/// Rigid-body reference: the block's four corners against the slab's top face and the slab's
/// corner (0, 0) against the block's faces, frictionless penalty springs kn that only push,
/// velocity Verlet at a step a thousand times shorter than the contact period. Returns the
/// block's rotation at end_time, radians.
double rigid_slide_off_rotation(const SlideOff& p) {
  const double mass = p.density * 4.0 * p.half * p.half;
  const double inertia = mass * (8.0 * p.half * p.half) / 12.0;
  const double dt = 2e-3 * std::sqrt(mass / p.kn);
  double x = p.start_x, y = p.half, th = 0.0, vx = p.speed, vy = 0.0, w = 0.0;
  auto forces = [&](double& fx, double& fy, double& m) {
    fx = 0.0;
    fy = -mass * kG;
    m = 0.0;
    const double c = std::cos(th), s = std::sin(th);
    const std::array<std::array<double, 2>, 4> corners{
        {{-p.half, -p.half}, {p.half, -p.half}, {p.half, p.half}, {-p.half, p.half}}};
    for (const auto& k : corners) {  // a corner below the slab's top face, over the slab
      const double rx = c * k[0] - s * k[1], ry = s * k[0] + c * k[1];
      const double px = x + rx, py = y + ry;
      if (px > 0.0 || px < -p.slab_length || py >= 0.0 || py < -p.half) continue;
      const double f = -p.kn * py;
      fy += f;
      m += rx * f;
    }
    // The slab's corner against the block: the face it lies behind by the least.
    const double qx = c * (0.0 - x) + s * (0.0 - y), qy = -s * (0.0 - x) + c * (0.0 - y);  // in the block frame
    const double depth = p.half - std::max(std::abs(qx), std::abs(qy));
    if (depth <= 0.0) return;
    double nx = 0.0, ny = 0.0;  // push direction on the block, block frame
    if (std::abs(qy) >= std::abs(qx))
      ny = qy > 0.0 ? -1.0 : 1.0;
    else
      nx = qx > 0.0 ? -1.0 : 1.0;
    const double fxb = p.kn * depth * nx, fyb = p.kn * depth * ny;
    const double gx = c * fxb - s * fyb, gy = s * fxb + c * fyb;
    fx += gx;
    fy += gy;
    m += (0.0 - x) * gy - (0.0 - y) * gx;
  };
  double fx, fy, m;
  forces(fx, fy, m);
  for (double t = 0.0; t < p.end_time - 0.5 * dt; t += dt) {
    vx += 0.5 * dt * fx / mass;
    vy += 0.5 * dt * fy / mass;
    w += 0.5 * dt * m / inertia;
    x += dt * vx;
    y += dt * vy;
    th += dt * w;
    forces(fx, fy, m);
    vx += 0.5 * dt * fx / mass;
    vy += 0.5 * dt * fy / mass;
    w += 0.5 * dt * m / inertia;
  }
  return th;
}

Engine slide_off_engine(const SlideOff& p, double allowed_displacement) {
  auto s = basic_scene(scene::Mode::Dynamic, 0.01, p.kn, {0.0, -kG});
  s.materials[0].density = p.density;
  s.materials[0].young = 1e12;  // a rigid block: strain 1e-8 under its own weight
  s.analysis.end_time = p.end_time;
  s.bodies = {body("block"), body("slab", scene::Motion::Fixed)};
  s.bodies[0].initial_velocity = {p.speed, 0.0};
  meshes::Mesh m;
  add_rectangle(m, "block", p.start_x - p.half, 0.0, p.start_x + p.half, 2.0 * p.half);
  add_rectangle(m, "slab", -p.slab_length, -10.0, 0.0, 0.0);
  EngineOptions o;
  o.allowed_displacement = allowed_displacement;
  return Engine(s, m, o);
}
}  // namespace

// A closed contact that would pull held the block level 1.7 m past the slab's edge (it turned
// -7.85° by 5 s in the version of this case). Released as soon as it would pull, the
// block tips as the rigid-body reference does. The contact period (11 ms) is about the scene's
// step (10 ms), so the DDA's first-order time error is large at the scene's allowed step
// displacement; it falls with the step (measured: 2.7°, 2.1°, 0.095° at 0.5, 0.05, 0.005 m;
// 12.9°, 2.8°, 0.18° before a corner inside the other block always had a contact), so the test
// asserts that convergence.
BOOST_AUTO_TEST_CASE(block_sliding_off_an_edge_tips_like_a_rigid_body) {
  const SlideOff p;
  const double reference = rigid_slide_off_rotation(p);
  std::vector<double> error;
  for (double allowed : {0.5, 0.05, 0.005}) {
    Engine e = slide_off_engine(p, allowed);
    while (e.time() < p.end_time * (1.0 - 1e-12)) e.step(p.end_time - e.time());
    const double got = block_angle(e, 0);
    BOOST_TEST_MESSAGE("slide-off rotation at " << p.end_time << " s, allowed step " << allowed << " m: DDA "
                                                << got / kDegree << "°, rigid reference " << reference / kDegree
                                                << "°, largest balance error " << e.ledger().largest_balance_error);
    BOOST_TEST(e.ledger().largest_balance_error <= 1e-3);
    error.push_back(std::abs(got - reference));
  }
  BOOST_TEST(reference / kDegree < -45.0);
  BOOST_TEST(error[0] <= 15.0 * kDegree);
  BOOST_TEST(error[1] <= 4.0 * kDegree);
  BOOST_TEST(error[2] <= 0.3 * error[1]);
}

namespace {
/// Largest ledger gain over a run: max over steps of stored − (initial + work), J/m.
struct LedgerWatch {
  double largest_gain = -1e300;
  void operator()(const StepReport& r) {
    largest_gain = std::max(largest_gain, r.ledger.stored.stored() - (r.ledger.initial + r.ledger.work()));
  }
};

/// The synthetic impact disc with unbreakable virtual joints, no friction, no gravity, and every
/// contact spring kn = ratio·E.
scene::Scene bonded_frictionless_impact(double kn_over_e) {
  scene::Scene s = make_impact_scene(3.5, 1.0);
  const double kn = kn_over_e * s.materials[0].young;
  for (auto& js : s.joint_sets) {
    js.friction_angle = 0.0;
    js.cohesion = js.tensile_strength = 1e30;
    js.normal_stiffness = kn;
    js.shear_stiffness = 0.4 * kn;
  }
  s.joint_sets[1].cohesion = s.joint_sets[1].tensile_strength = 0.0;
  s.analysis.penalty = kn;
  s.analysis.gravity = {0.0, 0.0};
  return s;
}
}  // namespace

// A bonded, unbreakable disc hits a fixed plate without friction: only the time scheme can
// dissipate and nothing can add energy. Stiff contacts were where energy appeared before
// (the stability study's kn/E = 1e3 and 1e4 gained 5.8x and 51.6x). Bounds: no step stores more
// than the initial energy + 0.5% of it; the ledger closes within 1%.
BOOST_AUTO_TEST_CASE(bonded_disc_hitting_a_plate_never_gains_energy_at_any_stiffness) {
  const meshes::Mesh mesh = make_ring_disc_mesh(0.1, 300);
  for (double ratio : {1.0, 1e2, 1e3, 1e4}) {
    EngineOptions o;
    o.solver.kind = SolverKind::Direct;
    Engine e(bonded_frictionless_impact(ratio), mesh, o);
    LedgerWatch watch;
    for (int k = 0; k < 2000; ++k) watch(e.step());
    const EnergyLedger& l = e.ledger();
    BOOST_TEST_MESSAGE("kn/E = " << ratio << ": initial " << l.initial << " J/m, stored " << l.stored.stored()
                                 << ", numerical " << l.total.numerical << ", largest gain " << watch.largest_gain
                                 << ", largest balance error " << l.largest_balance_error << ", missed contacts "
                                 << e.statistics().missed_contacts << ", dt cuts "
                                 << e.statistics().cuts_displacement + e.statistics().cuts_open_close);
    BOOST_TEST(watch.largest_gain <= 0.005 * l.initial);
    BOOST_TEST(l.largest_balance_error <= 0.01);
    BOOST_TEST(e.statistics().missed_contacts == 0);
  }
}

// A fan of six triangles around one node, squeezed until its joints yield and break: the
// triangles that meet only at the node never overlap deeper than one step's allowed
// displacement (measured geometrically, vertex inside triangle), before and after the breaks,
// and the ledger closes within 1%.
BOOST_AUTO_TEST_CASE(fan_around_a_node_squeezed_to_failure_never_overlaps_unseen) {
  Fan fan;
  EngineOptions o;
  o.allowed_displacement = 2e-6;
  Engine e(fan.scene, fan.mesh, o);
  double deepest = 0.0;
  long steps_after_break = 0;
  while (e.time() < 1e-3 && steps_after_break < 3000) {
    e.step();
    if (e.crack_counts().total > 0) ++steps_after_break;
    for (Index p = 0; p < 6; ++p)
      for (Index q = 0; q < 6; ++q)
        if ((p - q + 6) % 6 >= 2 && (p - q + 6) % 6 <= 4)
          deepest = std::max(deepest, deepest_vertex_inside(e.blocks(), p, q));
  }
  const EnergyLedger& l = e.ledger();
  BOOST_TEST_MESSAGE("fan: " << e.crack_counts().total << " joints broken by t = " << e.time()
                             << " s, deepest overlap of "
                             << "node-sharing triangles " << deepest << " m (allowed " << e.allowed_displacement()
                             << "), supports' work " << l.total.work_supports << " J/m, released by breaks "
                             << l.total.joint_breaks << ", largest balance error " << l.largest_balance_error);
  BOOST_TEST(e.crack_counts().total >= 1);
  BOOST_TEST(steps_after_break >= 1000);
  BOOST_TEST(deepest <= e.allowed_displacement());
  BOOST_TEST(l.largest_balance_error <= 0.01);
  BOOST_TEST(e.statistics().missed_contacts == 0);
}

namespace {
Eigen::Vector2d linear_momentum(const Engine& e) {
  Eigen::Vector2d p = Eigen::Vector2d::Zero();
  for (std::size_t b = 0; b < e.blocks().block_count(); ++b)
    p += e.blocks().mass[b] * Eigen::Vector2d(e.blocks().velocity[b][kU], e.blocks().velocity[b][kV]);
  return p;
}
}  // namespace

// A fragment knocked free of its parent flies back into it at 5 m/s: one triangle of the fan
// with its two joints broken, moved 0.5 mm out and sent back along the bisector; nothing is
// fixed and there is no gravity, so momentum is conserved to round-off (1e-9 relative) and the
// ledger closes within 1%.
BOOST_AUTO_TEST_CASE(fragment_hitting_its_parent_again_conserves_momentum_and_energy) {
  Fan fan;
  fan.scene.bodies.resize(1);
  fan.mesh = meshes::Mesh{};
  Fan full;
  fan.mesh.nodes = full.mesh.nodes;
  fan.mesh.body_names = {"fan"};
  fan.mesh.cell_nodes.assign(full.mesh.cell_nodes.begin(), full.mesh.cell_nodes.begin() + 18);
  fan.mesh.cell_offsets.assign(full.mesh.cell_offsets.begin(), full.mesh.cell_offsets.begin() + 7);
  fan.mesh.cell_body.assign(6, 0);
  fan.scene.joint_sets[1].tensile_strength = fan.scene.joint_sets[1].cohesion = 1e30;
  EngineOptions o;
  o.allowed_displacement = 2e-6;
  o.solver.kind = SolverKind::Direct;  // momentum to round-off needs the system solved to round-off
  Engine e(fan.scene, fan.mesh, o);
  BlockSystem& s = e.blocks();
  for (Joint& j : s.joints)
    if (j.block_a == 0 || j.block_b == 0) j.broken = true;
  const double bisector = 30.0 * kDegree, offset = 5e-4, speed = 5.0;
  for (Index v = s.begin(0); v < s.end(0); ++v) {
    s.vx[v] += offset * std::cos(bisector);
    s.vy[v] += offset * std::sin(bisector);
  }
  update_block_geometry(s);
  s.velocity[0][kU] = -speed * std::cos(bisector);
  s.velocity[0][kV] = -speed * std::sin(bisector);
  const Eigen::Vector2d p0 = linear_momentum(e);
  double momentum_error = 0.0;
  for (int k = 0; k < 4000; ++k) {
    e.step();
    momentum_error = std::max(momentum_error, (linear_momentum(e) - p0).norm() / p0.norm());
  }
  const EnergyLedger& l = e.ledger();
  const double fragment_speed = std::hypot(s.velocity[0][kU], s.velocity[0][kV]);
  BOOST_TEST_MESSAGE("fragment: momentum error "
                     << momentum_error << ", fragment speed after " << fragment_speed << " m/s, stored "
                     << l.stored.stored() << " of " << l.initial << " J/m, friction " << l.total.friction
                     << ", numerical " << l.total.numerical << ", largest balance error " << l.largest_balance_error);
  BOOST_TEST(s.velocity[0][kU] * std::cos(bisector) + s.velocity[0][kV] * std::sin(bisector) > 0.0);  // it bounced
  BOOST_TEST(momentum_error <= 1e-9);
  BOOST_TEST(l.largest_balance_error <= 0.01);
  BOOST_TEST(e.statistics().missed_contacts == 0);
}

// Shi's linear rotation update makes a rotating block grow (area ·(1 + r²) per step); ddafrac
// moves the vertices by the exact rotation, so a free block spinning through a whole turn keeps
// its area and its kinetic energy to round-off (1e-12 relative).
BOOST_AUTO_TEST_CASE(a_spinning_block_keeps_its_area_and_energy) {
  auto s = basic_scene(scene::Mode::Dynamic, 1e-4, 1e9, {0.0, 0.0});
  s.bodies = {body("block")};
  meshes::Mesh m;
  add_polygon(m, "block", {{0.0, 0.0}, {1.0, 0.0}, {1.2, 0.8}, {0.1, 0.6}});
  EngineOptions o;
  o.allowed_displacement = 1.0;
  Engine e(s, m, o);
  const double omega = 20.0;  // rad/s: 2e-3 rad per step, a whole turn in 3142 steps
  e.blocks().velocity[0][kR] = omega;
  const double area0 = e.blocks().geometry[0].area;
  const double kinetic0 = e.energies().kinetic;
  const int steps = static_cast<int>(std::ceil(2.0 * common::kPi / (omega * 1e-4)));
  for (int k = 0; k < steps; ++k) e.step();
  const double area_error = std::abs(e.blocks().geometry[0].area - area0) / area0;
  const double kinetic_error = std::abs(e.energies().kinetic - kinetic0) / kinetic0;
  BOOST_TEST_MESSAGE("spinning block after " << steps << " steps (" << steps * omega * 1e-4 << " rad): area error "
                                             << area_error << ", kinetic energy error " << kinetic_error
                                             << ", strain energy " << e.energies().strain << " J/m");
  BOOST_TEST(area_error <= 1e-12);
  BOOST_TEST(kinetic_error <= 1e-12);
  BOOST_TEST(e.ledger().largest_balance_error <= 1e-12);
}

// A sharp corner driven tip first into a square block's corner: the two wedges point at each
// other, so they are far apart in angle (about 2 rad, no vertex-vertex contact), and the tip
// arrives within the vertex-vertex capture radius of the square's corner, where no vertex-edge
// contact is formed. Once inside the square it must be held all the same: the tip never lies
// deeper inside than one step's allowed displacement (measured geometrically, as for the fan
// above), no contact is found already that deep, and the ledger closes within 1% (a contact
// first found deep adds ½·kn·d² at once; before a vertex inside another block always had a
// contact the tip reached 3.3 µm unseen and the balance error was 724%; measured now: 0.23 and
// 0.19 µm, 0.33% and 0.066%). At 40° one contact still comes in deep by its energy
// (Statistics::missed_contacts): found 0.064 µm deep, its spring took 0.26% of the balance's
// scale at once, most of the 0.33%. Two approach directions, so that neither is symmetric about
// the square's diagonal; frictionless, the tip glances off along one face.
BOOST_AUTO_TEST_CASE(a_tip_driven_into_a_corner_is_held_as_soon_as_it_is_inside) {
  const double tip_half_angle = 20.0 * kDegree, side = 5e-3, speed = 1.0;  // rad, m, m/s
  const double kn = 1e10;                                                  // N/m
  for (const double heading : {40.0 * kDegree, 55.0 * kDegree}) {
    auto s = basic_scene(scene::Mode::Dynamic, 1e-7, kn, {0.0, 0.0});
    s.bodies = {body("striker"), body("wall", scene::Motion::Fixed)};
    meshes::Mesh m;
    // The striker's tip 20 µm short of the square's corner (the origin) along its heading.
    const double gap = 20e-6, back = heading + common::kPi;
    const meshes::Point tip{-gap * std::cos(heading), -gap * std::sin(heading)};
    auto ray = [&](double a) { return meshes::Point{tip.x + side * std::cos(a), tip.y + side * std::sin(a)}; };
    add_polygon(m, "striker", {tip, ray(back - tip_half_angle), ray(back + tip_half_angle)});
    add_rectangle(m, "wall", 0.0, 0.0, side, side);
    EngineOptions o;
    o.allowed_displacement = 2e-6;  // m: a search distance of 5 µm, the capture radius the same
    Engine e(s, m, o);
    BlockSystem& b = e.blocks();
    b.velocity[0][kU] = speed * std::cos(heading);
    b.velocity[0][kV] = speed * std::sin(heading);
    double deepest = 0.0;
    for (int k = 0; k < 600; ++k) {  // 60 µs: 20 to arrive, about 4 in contact
      e.step();
      deepest = std::max(deepest, deepest_vertex_inside(b, 0, 1));
    }
    const EnergyLedger& l = e.ledger();
    const ResidualSources& rs = l.residual_sources;
    BOOST_TEST_MESSAGE("tip first at " << heading / kDegree << " deg: deepest " << deepest << " m (allowed "
                                       << e.allowed_displacement() << "), stored " << l.stored.stored() << " of "
                                       << l.initial << " J/m, largest balance error " << l.largest_balance_error
                                       << ", missed " << e.statistics().missed_contacts << "; residual " << l.residual()
                                       << " J/m: kept " << rs.contacts_kept << ", reclosed " << rs.contacts_reclosed
                                       << ", new " << rs.contacts_new << ", blocks " << rs.blocks << ", supports "
                                       << rs.supports);
    BOOST_TEST(deepest <= e.allowed_displacement());
    BOOST_TEST(e.statistics().deepest_missed <= e.allowed_displacement());
    BOOST_TEST(l.largest_balance_error <= 0.01);
    // The ledger says where its residual came from: the contacts that took a new line already
    // overlapping (99.93% at 40°, 99.7% at 55°). What the moved geometry re-measures on the kept
    // contacts and the blocks is second order in a step's motion (0.1–0.4%).
    BOOST_TEST(std::abs(l.residual() - rs.total()) <= testing::kResidualRoundOff * l.scale());
    BOOST_TEST(rs.contacts_new >= 0.99 * l.residual());
  }
}

// An open contact closes only once it overlaps by more than the open-close band (docs/design.md
// §4.4), so an overlap inside the band builds up with no spring acting; the spring then pushes
// from the overlap the contact started its step with (Contact::rest_gap). A block set down on a
// fixed base overlapping it by half the band stays at rest: no force, no energy. Overlapping by
// three bands, it is pushed off with what its two corners' springs store beyond the band,
// 2·½·kn·(2·band)², not 2·½·kn·(3·band)² (2.25 times that); the implicit scheme keeps 81% of it
// (the lower bound: half). Before the rest gap, every re-closing inside the band added
// up to ½·kn·band²: at kn = 100·E the node contacts of case 4 (1393 blocks) re-closed often
// enough for that to be the whole of a steady balance drift (0.36% at 1800 µs).
BOOST_AUTO_TEST_CASE(an_overlap_inside_the_open_close_band_stores_no_energy) {
  const double kn = 1e9, dt = 1e-4;  // N/m, s: about 37 steps per contact period
  for (const double bands : {0.5, 3.0}) {
    auto s = basic_scene(scene::Mode::Dynamic, dt, kn, {0.0, 0.0});
    s.bodies = {body("block"), body("base", scene::Motion::Fixed)};
    EngineOptions o;
    o.allowed_displacement = 1e-3;  // m
    const double band = o.state_tolerance * o.allowed_displacement;
    const double overlap = bands * band;
    meshes::Mesh m;
    add_rectangle(m, "block", 0.25, -overlap, 0.75, 0.5 - overlap);
    add_rectangle(m, "base", 0.0, -1.0, 1.0, 0.0);
    Engine e(s, m, o);
    for (int k = 0; k < 200; ++k) e.step();
    const double stored = e.energies().stored();
    const int corners = 2;  // the block's bottom corners against the base's top face
    const double beyond_band = corners * spring_energy(kn, std::max(overlap - band, 0.0));
    BOOST_TEST_MESSAGE(bands << " bands of overlap: stored after 200 steps " << stored
                             << " J/m; the spring beyond the band " << beyond_band << ", from zero gap "
                             << corners * spring_energy(kn, overlap) << ", block speed " << e.blocks().velocity[0][kV]
                             << " m/s");
    if (bands < 1.0) {
      BOOST_TEST(stored <= 1e-12 * spring_energy(kn, overlap));
    } else {
      BOOST_TEST(e.blocks().velocity[0][kV] > 0.0);
      BOOST_TEST(stored <= beyond_band * (1.0 + 1e-9));
      BOOST_TEST(stored >= 0.5 * beyond_band);
    }
  }
}
