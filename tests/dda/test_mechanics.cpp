// Verification of the DDA mechanics against closed-form answers (issue 3, tests 1-6).
#define BOOST_TEST_MODULE dda_mechanics
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/dda/engine.hpp"
#include "support.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;
using testing::add_rectangle;
using testing::basic_scene;
using testing::body;

namespace {
constexpr double kG = 9.81;  // m/s^2
using common::kPi;

double centroid_x(const Engine& e, Index b) { return e.blocks().geometry[static_cast<std::size_t>(b)].cx; }
double centroid_y(const Engine& e, Index b) { return e.blocks().geometry[static_cast<std::size_t>(b)].cy; }

/// A free 1 m square block on a fixed 10 m x 1 m base, friction angle phi, gravity g.
Engine block_on_base(scene::Mode mode, double dt, double phi, scene::Vec2 g, double kn) {
  auto s = basic_scene(mode, dt, kn, g);
  s.joint_sets[0].friction_angle = phi;
  s.bodies = {body("block"), body("base", scene::Motion::Fixed)};
  meshes::Mesh m;
  add_rectangle(m, "block", -0.5, 0.0, 0.5, 1.0);
  add_rectangle(m, "base", -5.0, -1.0, 5.0, 0.0);
  EngineOptions o;
  o.allowed_displacement = 0.01;
  return Engine(s, m, o);
}
}  // namespace

// 1. Free fall. Newmark γ=1, β=½ integrates constant acceleration exactly; the only error is
// round-off over 1000 steps (~1e-13), so 1e-9 relative is a strict but safe bound.
BOOST_AUTO_TEST_CASE(free_fall_matches_half_g_t_squared) {
  auto s = basic_scene(scene::Mode::Dynamic, 1e-3, 1e9, {0.0, -kG});
  s.bodies = {body("block")};
  meshes::Mesh m;
  add_rectangle(m, "block", 0.0, 0.0, 1.0, 1.0);
  EngineOptions o;
  o.allowed_displacement = 1.0;
  Engine e(s, m, o);
  const double y0 = centroid_y(e, 0);
  for (int k = 0; k < 1000; ++k) e.step();
  const double t = e.time();
  const double expected = -0.5 * kG * t * t;
  const double got = centroid_y(e, 0) - y0;
  BOOST_TEST_MESSAGE("free fall: t = " << t << " s, displacement " << got << " m, rel. error "
                                       << std::abs(got - expected) / std::abs(expected));
  BOOST_TEST(std::abs(t - 1.0) < 1e-12);
  BOOST_TEST(std::abs(got - expected) <= 1e-9 * std::abs(expected));
  BOOST_TEST(std::abs(e.blocks().velocity[0][kV] + kG * t) <= 1e-9 * kG * t);
}

// 1b. Mass damping (analysis.mass_damping = η) on a free block moving as a whole. The scheme's
// end velocity V1 = 2D/Δt − V0 with M·a1 = −η·M·V1 gives V1 = V0/(1 + η·Δt) each step: after n
// steps V0/(1 + η·Δt)^n exactly, up to round-off (1e-12 relative after 1000 steps). Against the
// ODE's V0·exp(−η·t) the scheme lags by exp(n·(η·Δt − ln(1 + η·Δt))) − 1 ≤ exp(n·(η·Δt)²/2) − 1
// (1.3% here), and never decays faster. The ledger books the kinetic energy the damping force
// took as damping_dissipation, to round-off, and closes.
BOOST_AUTO_TEST_CASE(mass_damping_slows_a_free_block_as_the_scheme_says) {
  constexpr double eta = 5.0;  // 1/s
  constexpr double dt = 1e-3;  // s
  constexpr int steps = 1000;
  auto s = basic_scene(scene::Mode::Dynamic, dt, 1e9, {0.0, 0.0});
  s.analysis.mass_damping = eta;
  s.bodies = {body("block")};
  s.bodies[0].initial_velocity = {1.0, -0.5};
  meshes::Mesh m;
  add_rectangle(m, "block", 0.0, 0.0, 1.0, 1.0);
  EngineOptions o;
  o.allowed_displacement = 1.0;
  Engine e(s, m, o);
  const double kinetic0 = e.energies().kinetic;
  for (int k = 0; k < steps; ++k) e.step();
  const double t = e.time();
  const double scheme = std::pow(1.0 + eta * dt, -steps);
  const double ode = std::exp(-eta * t);
  const Vec6& v = e.blocks().velocity[0];
  const EnergyLedger& l = e.ledger();
  const double kinetic_lost = kinetic0 - e.energies().kinetic;
  BOOST_TEST_MESSAGE("mass damping: u " << v[kU] << " m/s, scheme " << scheme << ", exp(-eta t) " << ode
                                        << "; kinetic lost " << kinetic_lost << " J/m, damping booked "
                                        << l.total.damping << ", balance error " << l.balance_error());
  BOOST_TEST(std::abs(v[kU] / scheme - 1.0) <= 1e-12);
  BOOST_TEST(std::abs(v[kV] / (-0.5 * scheme) - 1.0) <= 1e-12);
  BOOST_TEST(v[kU] / ode - 1.0 >= 0.0);
  BOOST_TEST(v[kU] / ode - 1.0 <= std::expm1(steps * eta * dt * eta * dt / 2.0));
  BOOST_TEST(std::abs(l.total.damping / kinetic_lost - 1.0) <= 1e-10);
  BOOST_TEST(std::abs(l.total.numerical) <= 1e-12 * kinetic0);
  BOOST_TEST(std::abs(l.balance_error()) <= 1e-12);
}

// 2a. Incline steeper than φ (gravity tilted by α instead of tilting the base): the block slides
// with a = g (sin α − cos α tan φ). The normal force settles within a few steps (γ=1 damps the
// contact oscillation), so the displacement after 0.5 s matches within 1%.
BOOST_AUTO_TEST_CASE(block_slides_down_steep_incline) {
  const double alpha = 30.0 * kPi / 180.0, phi = 20.0 * kPi / 180.0;
  Engine e = block_on_base(scene::Mode::Dynamic, 1e-3, phi, {kG * std::sin(alpha), -kG * std::cos(alpha)}, 1e10);
  const double x0 = centroid_x(e, 0);
  while (e.time() < 0.5 - 1e-12) e.step(0.5 - e.time());
  const double t = e.time();
  const double expected = 0.5 * kG * (std::sin(alpha) - std::cos(alpha) * std::tan(phi)) * t * t;
  const double got = centroid_x(e, 0) - x0;
  BOOST_TEST_MESSAGE("incline 30/20: slid " << got << " m, expected " << expected << " m, rel. error "
                                            << std::abs(got - expected) / expected);
  BOOST_TEST(std::abs(got - expected) <= 0.01 * expected);
}

// 2b. Incline shallower than φ: the block stays put. The only admissible motion is the elastic
// deflection of the two shear springs, W sin α / (2 ks) ≈ 4e-7 m; we allow 1e-6 m.
BOOST_AUTO_TEST_CASE(block_stays_on_shallow_incline) {
  const double alpha = 10.0 * kPi / 180.0, phi = 20.0 * kPi / 180.0;
  Engine e = block_on_base(scene::Mode::Dynamic, 1e-3, phi, {kG * std::sin(alpha), -kG * std::cos(alpha)}, 1e10);
  const double x0 = centroid_x(e, 0);
  for (int k = 0; k < 500; ++k) e.step();
  const double drift = std::abs(centroid_x(e, 0) - x0);
  BOOST_TEST_MESSAGE("incline 10/20: drift " << drift << " m after " << e.time() << " s");
  BOOST_TEST(drift < 1e-6);
}

// 3. Block resting on a fixed base (static mode): the contact forces carry the weight. Static
// steps converge geometrically to equilibrium, so 0.1% is reached well within 100 steps; the
// penetration of each of the two vertex contacts is W/(2 kn).
BOOST_AUTO_TEST_CASE(resting_block_contact_force_equals_weight) {
  const double kn = 1e9;
  Engine e = block_on_base(scene::Mode::Static, 1e-2, 0.5, {0.0, -kG}, kn);
  for (int k = 0; k < 100; ++k) e.step();
  const double weight = 2000.0 * 1.0 * kG;
  double force = 0.0;
  int closed = 0;
  double pen = 0.0;
  for (const Contact& c : e.contacts().contacts) {
    if (c.state == ContactState::Open) continue;
    ++closed;
    force += c.normal_force;
    pen = std::max(pen, -c.d_iter);
  }
  BOOST_TEST_MESSAGE("resting: " << closed << " closed contacts, force " << force << " N/m vs weight " << weight
                                 << ", penetration " << pen << " m vs W/(2kn) " << weight / (2 * kn));
  BOOST_TEST(closed == 2);
  BOOST_TEST(std::abs(force - weight) <= 1e-3 * weight);
  BOOST_TEST(std::abs(pen - weight / (2.0 * kn)) <= 1e-2 * weight / (2.0 * kn));
}

// 4. Uniaxial load on one elastic block (point loads σh/2 at the four corners, no supports):
// the block strain is uniform and exact, εx = σ/E (plane stress) or (1−ν²)σ/E (plane strain).
// With σ/E = 1e-7 the geometric nonlinearity is ~1e-7 relative, inertia at dt = 1 s is ~3e-8:
// both under the 1e-6 relative tolerance.
namespace {
void uniaxial(scene::PlaneModel plane, double expected_ex, double expected_ey) {
  auto s = basic_scene(scene::Mode::Static, 1.0, 1e9, {0.0, 0.0});
  s.analysis.plane = plane;
  s.bodies = {body("block")};
  meshes::Mesh m;
  add_rectangle(m, "block", 0.0, 0.0, 1.0, 1.0);
  const double sigma = 1e3;  // Pa; h = 1 m so the edge force is σ·h
  EngineOptions o;
  o.allowed_displacement = 0.01;
  o.point_loads = {{0, 1.0, 0.0, 0.5 * sigma, 0.0},
                   {0, 1.0, 1.0, 0.5 * sigma, 0.0},
                   {0, 0.0, 0.0, -0.5 * sigma, 0.0},
                   {0, 0.0, 1.0, -0.5 * sigma, 0.0}};
  Engine e(s, m, o);
  for (int k = 0; k < 5; ++k) e.step();
  const auto& b = e.blocks();
  const double ex = 0.5 * ((b.vx[1] - b.vx[0]) + (b.vx[2] - b.vx[3])) - 1.0;
  const double ey = 0.5 * ((b.vy[3] - b.vy[0]) + (b.vy[2] - b.vy[1])) - 1.0;
  BOOST_TEST_MESSAGE("uniaxial " << (plane == scene::PlaneModel::Stress ? "plane stress" : "plane strain") << ": ex "
                                 << ex << " (expected " << expected_ex << "), ey " << ey << " (expected " << expected_ey
                                 << "), σxx " << b.stress[0][0]);
  BOOST_TEST(std::abs(ex - expected_ex) <= 1e-6 * std::abs(expected_ex));
  BOOST_TEST(std::abs(ey - expected_ey) <= 1e-6 * std::abs(expected_ey));
  BOOST_TEST(std::abs(b.stress[0][0] - sigma) <= 1e-6 * sigma);
}
}  // namespace

BOOST_AUTO_TEST_CASE(uniaxial_plane_stress) {
  const double E = 1e10, nu = 0.2, sigma = 1e3;
  uniaxial(scene::PlaneModel::Stress, sigma / E, -nu * sigma / E);
}

BOOST_AUTO_TEST_CASE(uniaxial_plane_strain) {
  const double E = 1e10, nu = 0.2, sigma = 1e3;
  uniaxial(scene::PlaneModel::Strain, (1 - nu * nu) * sigma / E, -nu * (1 + nu) * sigma / E);
}

// 5. Frictionless collision of two blocks of different density. Contact forces are equal and
// opposite by construction (e and g have opposite translational parts), the direct solver leaves
// a residual of ~1e-16, so momentum is conserved to round-off: 1e-9 relative is safe.
BOOST_AUTO_TEST_CASE(frictionless_collision_conserves_momentum) {
  auto s = basic_scene(scene::Mode::Dynamic, 1e-4, 1e9, {0.0, 0.0});
  s.materials.push_back({"dense", 3000.0, 1e10, 0.2});
  s.bodies = {body("a"), body("b", scene::Motion::Free, 1)};
  s.bodies[0].initial_velocity = {1.0, 0.0};
  meshes::Mesh m;
  add_rectangle(m, "a", 0.0, 0.0, 1.0, 1.0);
  add_rectangle(m, "b", 1.001, 0.0, 2.001, 1.0);
  EngineOptions o;
  o.allowed_displacement = 1e-3;
  o.solver.kind = SolverKind::Direct;
  Engine e(s, m, o);
  auto momentum = [&] {
    double p = 0.0;
    for (std::size_t b = 0; b < 2; ++b) p += e.blocks().mass[b] * e.blocks().velocity[b][kU];
    return p;
  };
  const double p0 = momentum();
  double worst = 0.0;
  for (int k = 0; k < 300; ++k) {
    e.step();
    worst = std::max(worst, std::abs(momentum() - p0) / std::abs(p0));
  }
  const double vb = e.blocks().velocity[1][kU];
  BOOST_TEST_MESSAGE("collision: p0 " << p0 << ", worst rel. momentum error " << worst << ", v_a "
                                      << e.blocks().velocity[0][kU] << ", v_b " << vb);
  BOOST_TEST(vb > 0.1);  // the collision did happen
  BOOST_TEST(worst <= 1e-9);
}

// 6. A 3 x 3 wall of 0.5 m blocks on a fixed base settles under gravity: no sideways drift beyond
// elastic shear deflection (< 1e-5 m), kinetic energy decays to a negligible level, and the
// mechanical energy never exceeds the potential energy released (the γ=1 scheme only dissipates).
BOOST_AUTO_TEST_CASE(wall_settles_without_drift) {
  auto s = basic_scene(scene::Mode::Dynamic, 1e-3, 1e9, {0.0, -kG});
  s.joint_sets[0].friction_angle = 30.0 * kPi / 180.0;
  meshes::Mesh m;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) add_rectangle(m, "wall", 0.5 * c, 0.5 * r, 0.5 * (c + 1), 0.5 * (r + 1));
  add_rectangle(m, "base", -1.0, -0.5, 2.5, 0.0);
  s.bodies = {body("wall"), body("base", scene::Motion::Fixed)};
  EngineOptions o;
  o.allowed_displacement = 1e-3;
  o.bond_virtual_joints = false;
  Engine e(s, m, o);
  const std::size_t nb = 9;
  std::vector<double> x0(nb), y0(nb);
  for (std::size_t b = 0; b < nb; ++b) {
    x0[b] = e.blocks().geometry[b].cx;
    y0[b] = e.blocks().geometry[b].cy;
  }
  const double mass = 2000.0 * 0.25;
  double max_excess = 0.0, ke_max = 0.0, ke_end = 0.0;
  for (int k = 0; k < 1000; ++k) {
    const StepReport r = e.step();
    double released = 0.0;
    for (std::size_t b = 0; b < nb; ++b) released += mass * kG * (y0[b] - e.blocks().geometry[b].cy);
    const double mech = r.energy.kinetic + r.energy.strain + r.energy.contact;
    max_excess = std::max(max_excess, mech - released);
    ke_max = std::max(ke_max, r.energy.kinetic);
    ke_end = r.energy.kinetic;
  }
  double drift = 0.0, settle = 0.0;
  for (std::size_t b = 0; b < nb; ++b) {
    drift = std::max(drift, std::abs(e.blocks().geometry[b].cx - x0[b]));
    settle = std::max(settle, y0[b] - e.blocks().geometry[b].cy);
  }
  const double scale = 9 * mass * kG * settle;
  BOOST_TEST_MESSAGE("wall: drift " << drift << " m, settlement " << settle << " m, KE max " << ke_max << " end "
                                    << ke_end << ", worst (mechanical - released) " << max_excess << " J vs scale "
                                    << scale);
  BOOST_TEST(drift < 1e-5);
  BOOST_TEST(settle < 1e-3);
  BOOST_TEST(ke_end < 1e-3 * ke_max);
  BOOST_TEST(max_excess <= 0.01 * scale);
}
