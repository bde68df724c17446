// Virtual joints and fracture (issue 4, tests 1-5): tensile and shear failure at the strength
// within one step's load increment, the failure type of joints over both limits, the effective
// modulus of a glued bar against kn/E, pre-broken joints behaving bit-for-bit like contacts
// that were never bonded, and the energy ledger closing across a break.
#define BOOST_TEST_MODULE dda_fracture
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/dda/run.hpp"
#include "ddafrac/dda/synthetic.hpp"
#include "support.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;
using testing::triangulated_bar;

namespace {

using common::kPi;

/// Rock-like scene with a virtual joint set (index 0) and a real one (index 1).
scene::Scene joint_scene(double dt, double kn, double tensile, double cohesion, double phi_deg) {
  scene::Scene s = testing::basic_scene(scene::Mode::Dynamic, dt, kn, {0.0, 0.0});
  scene::JointSet v;
  v.name = "virtual";
  v.friction_angle = phi_deg * kPi / 180.0;
  v.cohesion = cohesion;
  v.tensile_strength = tensile;
  v.normal_stiffness = kn;
  v.shear_stiffness = 0.4 * kn;
  s.joint_sets.insert(s.joint_sets.begin(), v);
  s.real_joints = 1;
  s.analysis.max_displacement_ratio = 0.05;
  scene::Body b = testing::body("rock");
  b.virtual_joints = 0;
  s.bodies.push_back(b);
  return s;
}

/// Two unit-size squares (side h) of one body sharing the edge x = h: block 0 left, block 1 right.
meshes::Mesh two_squares(double h) {
  meshes::Mesh m;
  m.body_names = {"rock"};
  m.nodes = {{0, 0}, {h, 0}, {2 * h, 0}, {2 * h, h}, {h, h}, {0, h}};
  m.cell_nodes = {0, 1, 4, 5, 1, 2, 3, 4};
  m.cell_offsets = {0, 4, 8};
  m.cell_body = {0, 0};
  return m;
}

/// The loads and ratios of the one row of a joint table (joints_document) with a single joint.
struct JointTableRow {
  double normal = 0.0, shear = 0.0, r1 = 0.0, r2 = 0.0, utilisation = 0.0;
  double stress_normal = 0.0, stress_shear = 0.0;  // the load the blocks' stress puts on the joint
};
JointTableRow only_joint_row(const std::string& table) {
  std::istringstream in(table);
  std::string header, line, rest;
  std::getline(in, header);
  BOOST_REQUIRE(std::getline(in, line));
  BOOST_REQUIRE(!std::getline(in, rest));
  BOOST_REQUIRE_EQUAL(header,
                      "t,joint,block_a,block_b,x,y,length,normal_force,shear_force,r1,r2,utilisation,"
                      "stress_normal_force,stress_shear_force");
  std::vector<double> v;
  std::istringstream fields(line);
  for (std::string f; std::getline(fields, f, ',');) v.push_back(std::stod(f));
  BOOST_REQUIRE_EQUAL(v.size(), 14u);
  return {v[7], v[8], v[9], v[10], v[11], v[12], v[13]};
}

/// Anchors on the four corners of a block moving at (vx, vy).
void hold(std::vector<Anchor>& out, Index block, const std::vector<meshes::Point>& corners, double vx, double vy) {
  for (const auto& p : corners) out.push_back({block, p.x, p.y, p.x, p.y, vx, vy});
}

/// two_squares with the left square held and the right one's anchors moving at (vx, vy) m/s.
Engine right_square_driven(const scene::Scene& sc, double h, double vx, double vy) {
  EngineOptions opt;
  hold(opt.anchors, 0, {{0, 0}, {0, h}}, 0.0, 0.0);
  hold(opt.anchors, 1, {{2 * h, 0}, {2 * h, h}}, vx, vy);
  return Engine(sc, two_squares(h), opt);
}

struct BreakRecord {
  int step = -1;
  JointForce before, at;  // joint force in the step before the break and in the breaking step
};

/// Steps until the joint of two_squares breaks (at most max_steps).
BreakRecord run_to_break(Engine& e, int max_steps) {
  BreakRecord r;
  JointForce prev;
  for (int k = 1; k <= max_steps; ++k) {
    const StepReport rep = e.step();
    const JointForce f = e.joint_forces().at(0);
    if (rep.new_cracks > 0) {
      r.step = k;
      r.before = prev;
      r.at = f;
      return r;
    }
    prev = f;
  }
  return r;
}

}  // namespace

// Test 1: pulled apart, the joint breaks in tension in the first step whose normal force exceeds
// σt·l; the overshoot is below that step's force increment.
BOOST_AUTO_TEST_CASE(tension_break_at_the_tensile_strength) {
  const double h = 0.01, sigma_t = 1e6;
  const scene::Scene sc = joint_scene(1e-6, 1e10, sigma_t, 1e7, 30.0);
  Engine e = right_square_driven(sc, h, 0.01, 0.0);
  BOOST_REQUIRE_EQUAL(e.blocks().joints.size(), 1u);
  const BreakRecord r = run_to_break(e, 5000);
  BOOST_REQUIRE(r.step > 1);
  const double limit = sigma_t * h;
  const double increment = r.at.normal - r.before.normal;
  BOOST_TEST_MESSAGE("tension: break at step " << r.step << ", f_n " << r.at.normal << " N/m vs σt·l " << limit
                                               << " N/m, step increment " << increment << " N/m");
  BOOST_TEST(r.before.normal <= limit);
  BOOST_TEST(r.at.normal > limit);
  BOOST_TEST(r.at.normal - limit <= increment);
  BOOST_TEST(increment < 0.05 * limit);  // the loading is resolved finely enough to mean something
  BOOST_REQUIRE_EQUAL(e.cracks().size(), 1u);
  const CrackEvent& c = e.cracks()[0];
  BOOST_TEST(static_cast<int>(c.type) == static_cast<int>(CrackType::Tensile));
  BOOST_TEST(std::abs(c.r1 - r.at.normal / limit) <= 1e-12);
  BOOST_TEST(std::abs(c.x - h) <= 1e-4 * h);
  BOOST_TEST(std::abs(c.y - 0.5 * h) <= 1e-4 * h);
  // From the next step on the joint is a real joint: it opens and carries no tension.
  for (int k = 0; k < 20; ++k) e.step();
  BOOST_TEST(e.joint_forces()[0].normal <= 0.0);
  BOOST_TEST(e.crack_counts().total == 1);
}

// Test 2: sheared under compression, the joint breaks in shear when |f_s| exceeds c·l + f_n·tanφ.
BOOST_AUTO_TEST_CASE(shear_break_under_compression) {
  const double h = 0.01, cohesion = 1e6, phi = 30.0;
  const scene::Scene sc = joint_scene(1e-6, 1e10, 1e7, cohesion, phi);
  Engine e = right_square_driven(sc, h, -0.01, 0.02);  // pushes in and slides up
  const BreakRecord r = run_to_break(e, 5000);
  BOOST_REQUIRE(r.step > 1);
  const double tan_phi = std::tan(phi * kPi / 180.0);
  auto excess = [&](const JointForce& f) {
    return std::abs(f.shear) - (cohesion * h + std::max(0.0, -f.normal) * tan_phi);
  };
  BOOST_TEST_MESSAGE("shear: break at step " << r.step << ", f_n " << r.at.normal << " N/m, f_s " << r.at.shear
                                             << " N/m, limit " << cohesion * h - r.at.normal * tan_phi << " N/m");
  BOOST_TEST(r.at.normal < 0.0);  // under compression
  BOOST_TEST(excess(r.before) <= 0.0);
  BOOST_TEST(excess(r.at) > 0.0);
  BOOST_TEST(excess(r.at) <= excess(r.at) - excess(r.before));
  BOOST_REQUIRE_EQUAL(e.cracks().size(), 1u);
  BOOST_TEST(static_cast<int>(e.cracks()[0].type) == static_cast<int>(CrackType::Shear));
  BOOST_TEST(e.cracks()[0].r2 > 1.0);
  BOOST_TEST(e.cracks()[0].r1 == 0.0);
}

// Test 3a: the utilisation map of the VTU snapshots. Two squares, the left one held at its left
// edge, the right one loaded at its right edge in static mode: in equilibrium the joint carries
// the load, so both blocks' utilisation is the load over the joint's strength, in tension
// (P / (σt·l)) and in shear under compression (S / (c·l + N·tanφ)). The joint's forces are measured
// along the held block's edge while the moment of the shear load turns the loaded block by about
// 2·S / (kn·l) ≈ 2.4e-4 rad, which mixes normal force into shear at that order (measured: 2.7e-4 of
// the utilisation; exact in tension); the solver's tolerance (1e-10) and static mode's inertia term
// (~1e-11 of the stiffness at Δt = 1 s) are far below. The joint table written beside each
// snapshot (joints_document) gives that joint's forces, the applied loads, and the same ratio;
// its blocks' stress puts the same load on it (stress_traction): nothing else carries load here.
BOOST_AUTO_TEST_CASE(utilisation_is_the_load_over_the_strength) {
  const double h = 0.01, sigma_t = 1e6, cohesion = 2e6, phi = 30.0, kn = 1e10;
  const double tan_phi = std::tan(phi * kPi / 180.0);
  struct Load {
    double normal, shear;  // N/m on the right block's right edge: +x pulls the joint open
    double expected;       // utilisation
  };
  const double tension = 0.4 * sigma_t * h, compression = 0.5 * cohesion * h, shear = 0.6 * cohesion * h;
  for (const Load& load : {Load{tension, 0.0, tension / (sigma_t * h)},
                           Load{-compression, shear, shear / (cohesion * h + compression * tan_phi)}}) {
    scene::Scene sc = joint_scene(1.0, kn, sigma_t, cohesion, phi);
    sc.analysis.mode = scene::Mode::Static;
    EngineOptions opt;
    hold(opt.anchors, 0, {{0, 0}, {0, h}}, 0.0, 0.0);
    for (const double y : {0.0, h}) opt.point_loads.push_back({1, 2 * h, y, 0.5 * load.normal, 0.5 * load.shear});
    Engine e(sc, two_squares(h), opt);
    for (int k = 0; k < 4; ++k) e.step();
    BOOST_REQUIRE(e.cracks().empty());
    const std::vector<double> u = e.joint_utilisation();
    BOOST_REQUIRE_EQUAL(u.size(), 2u);
    BOOST_TEST_MESSAGE("utilisation " << u[0] << ", " << u[1] << " against " << load.expected);
    BOOST_TEST(u[0] == u[1]);  // one joint, shared by both blocks
    BOOST_TEST(std::abs(u[0] - load.expected) <= 1e-3 * load.expected);
    // The snapshots' joint table: its one row is that joint, with the loads that make the ratios.
    const JointTableRow row = only_joint_row(joints_document(e));
    BOOST_TEST_MESSAGE("joint table: f_n " << row.normal << ", f_s " << row.shear << " N/m, r1 " << row.r1 << ", r2 "
                                           << row.r2 << ", utilisation " << row.utilisation);
    BOOST_TEST(row.utilisation == std::max(row.r1, row.r2));
    BOOST_TEST(std::abs(row.utilisation - u[0]) <= 1e-6 * u[0]);  // the table's 9 digits
    const double scale = std::abs(load.normal) + load.shear;      // N/m; the turn above mixes the two at 2.4e-4
    BOOST_TEST(std::abs(row.normal - load.normal) <= 1e-3 * scale);
    BOOST_TEST(std::abs(std::abs(row.shear) - load.shear) <= 1e-3 * scale);
    BOOST_TEST_MESSAGE("blocks' stress on the joint: f_n " << row.stress_normal << ", f_s " << row.stress_shear
                                                           << " N/m");
    BOOST_TEST(std::abs(row.stress_normal - row.normal) <= 1e-3 * scale);
    BOOST_TEST(std::abs(row.stress_shear - row.shear) <= 1e-3 * scale);
    // One joint, nothing else in contact: it carries all of its blocks' load.
    const JointLoadShare share = joint_load_share(e.blocks(), e.joint_forces());
    BOOST_TEST(share.joints == 1);
    BOOST_TEST(std::abs(share.normal - 1.0) <= 1e-3 * scale / std::abs(load.normal));
    if (load.shear > 0.0) BOOST_TEST(std::abs(share.shear - 1.0) <= 1e-3 * scale / load.shear);
  }
}

// Test 3b: a block without virtual joints (a platen) has no utilisation: kNoVirtualJoints, which
// the pictures draw grey, not 0 (which would read as an unloaded joint); a block whose joints
// carry nothing is at 0.
BOOST_AUTO_TEST_CASE(a_block_without_joints_has_no_utilisation) {
  const double h = 0.01;
  scene::Scene sc = joint_scene(1e-6, 1e10, 1e6, 1e6, 30.0);
  sc.bodies.push_back(testing::body("platen"));
  meshes::Mesh m = two_squares(h);
  m.body_names.push_back("platen");
  const double y0 = 2 * h;  // a square above the pair, apart from it
  for (const auto& p : {meshes::Point{0, y0}, {h, y0}, {h, y0 + h}, {0, y0 + h}}) m.nodes.push_back(p);
  for (meshes::Index k = 6; k < 10; ++k) m.cell_nodes.push_back(k);
  m.cell_offsets.push_back(12);
  m.cell_body.push_back(1);
  Engine e(sc, m, EngineOptions{});
  e.step();
  const std::vector<double> u = e.joint_utilisation();
  BOOST_REQUIRE_EQUAL(u.size(), 3u);
  BOOST_TEST(u[0] == 0.0);  // free and unloaded: the joint carries nothing
  BOOST_TEST(u[1] == 0.0);
  BOOST_TEST(u[2] == Engine::kNoVirtualJoints);
}

// Test 3: both ratios above one in the same step; the type follows the larger one.
BOOST_AUTO_TEST_CASE(type_follows_the_larger_ratio) {
  scene::JointSet js;
  js.tensile_strength = 1e6;
  js.cohesion = 2e6;
  js.friction_angle = 0.5;
  const double l = 0.01;
  FailureRatios a = failure_ratios({3e4, 2e4, 2}, l, js);  // r1 = 3, r2 = 1
  BOOST_TEST(a.r1 == 3.0);
  BOOST_TEST(a.r2 == 1.0);
  BOOST_TEST(a.broken());
  BOOST_TEST(static_cast<int>(a.type()) == static_cast<int>(CrackType::Tensile));
  a = failure_ratios({2e4, -8e4, 2}, l, js);  // r1 = 2, r2 = 4
  BOOST_TEST(static_cast<int>(a.type()) == static_cast<int>(CrackType::Shear));
  // In the engine: a sudden diagonal pull (shear about half the normal force) overloads both
  // limits in the first steps; a weak cohesion makes shear the larger ratio.
  for (const double cohesion : {1e3, 1e1}) {
    const double h = 0.01;
    const scene::Scene sc = joint_scene(1e-6, 1e10, 1e3, cohesion, 30.0);
    Engine e = right_square_driven(sc, h, 1.0, 0.5);
    for (int k = 0; k < 5 && e.cracks().empty(); ++k) e.step();
    BOOST_REQUIRE_EQUAL(e.cracks().size(), 1u);
    const CrackEvent& c = e.cracks()[0];
    BOOST_TEST_MESSAGE("c = " << cohesion << " Pa: r1 " << c.r1 << ", r2 " << c.r2 << ", " << to_string(c.type));
    BOOST_TEST(c.r1 > 1.0);
    BOOST_TEST(c.r2 > 1.0);
    BOOST_TEST(static_cast<int>(c.type) == static_cast<int>(c.r1 > c.r2 ? CrackType::Tensile : CrackType::Shear));
    BOOST_TEST(static_cast<int>(c.type) == static_cast<int>(cohesion > 1e2 ? CrackType::Tensile : CrackType::Shear));
  }
}

namespace {
/// E_eff of the glued bar in static tension: σ over the strain between two interior sections.
double effective_modulus(double young, double kn) {
  const double length = 0.1, height = 0.01, sigma = 1e6;
  const int nx = 20, ny = 2;
  scene::Scene sc = joint_scene(1.0, kn, 1e30, 1e30, 30.0);  // unbreakable joints
  sc.materials[0].young = young;
  sc.analysis.mode = scene::Mode::Static;
  sc.analysis.max_displacement_ratio = 0.01;  // search distance well below the element size
  const meshes::Mesh mesh = triangulated_bar(length, height, nx, ny);
  EngineOptions opt;
  // Left end held (x and y of its nodes), right end pulled by σ·H spread over its nodes.
  for (std::size_t c = 0; c + 1 < mesh.cell_offsets.size(); ++c)
    for (auto k = mesh.cell_offsets[c]; k < mesh.cell_offsets[c + 1]; ++k) {
      const auto& p = mesh.nodes[static_cast<std::size_t>(mesh.cell_nodes[static_cast<std::size_t>(k)])];
      if (p.x == 0.0) opt.anchors.push_back({static_cast<Index>(c), p.x, p.y, p.x, p.y, 0.0, 0.0});
    }
  std::vector<int> right_vertices;
  for (std::size_t c = 0; c + 1 < mesh.cell_offsets.size(); ++c)
    for (auto k = mesh.cell_offsets[c]; k < mesh.cell_offsets[c + 1]; ++k)
      if (mesh.nodes[static_cast<std::size_t>(mesh.cell_nodes[static_cast<std::size_t>(k)])].x == length)
        right_vertices.push_back(static_cast<int>(c));
  for (std::size_t c = 0; c + 1 < mesh.cell_offsets.size(); ++c)
    for (auto k = mesh.cell_offsets[c]; k < mesh.cell_offsets[c + 1]; ++k) {
      const auto& p = mesh.nodes[static_cast<std::size_t>(mesh.cell_nodes[static_cast<std::size_t>(k)])];
      if (p.x == length)
        opt.point_loads.push_back(
            {static_cast<Index>(c), p.x, p.y, sigma * height / static_cast<double>(right_vertices.size()), 0.0});
    }
  Engine e(sc, mesh, opt);
  const std::vector<double> x0 = e.blocks().vx;
  for (int k = 0; k < 4; ++k) e.step();
  // Mean x displacement of the vertices on the sections x = 0.25 L and x = 0.75 L.
  auto section = [&](double xs) {
    double sum = 0.0;
    int n = 0;
    for (std::size_t v = 0; v < x0.size(); ++v)
      if (std::abs(x0[v] - xs) < 1e-9) {
        sum += e.blocks().vx[v] - x0[v];
        ++n;
      }
    return sum / n;
  };
  const double strain = (section(0.75 * length) - section(0.25 * length)) / (0.5 * length);
  return sigma / strain;
}
}  // namespace

// Test 4: the joints add compliance in series with the blocks. With a normal spring kn (N/m per
// unit thickness, i.e. Pa) on every joint, a joint of length l carries σ·l over its two contacts,
// opening σ·l/(2kn) every ~l: 1/E_eff = 1/E + α/kn, α an O(1) constant of the mesh pattern (the
// diagonal joints add shear compliance through ks = 0.4 kn). So E/E_eff − 1 = α·E/kn: it must
// lie in (0, 2E/kn] and scale with E/kn (ratio of the deficits at kn = 10E and 100E within 10%
// of 10).
BOOST_AUTO_TEST_CASE(glued_bar_effective_modulus) {
  const double young = 1e10;
  const double e10 = effective_modulus(young, 10.0 * young);
  const double e100 = effective_modulus(young, 100.0 * young);
  const double deficit10 = young / e10 - 1.0, deficit100 = young / e100 - 1.0;
  BOOST_TEST_MESSAGE("E_eff/E = " << e10 / young << " (kn = 10 E), " << e100 / young
                                  << " (kn = 100 E); α = " << deficit10 * 10.0 << ", " << deficit100 * 100.0);
  BOOST_TEST(deficit10 > 0.0);
  BOOST_TEST(deficit100 > 0.0);
  BOOST_TEST(deficit10 <= 2.0 / 10.0);
  BOOST_TEST(deficit100 <= 2.0 / 100.0);
  BOOST_TEST(std::abs(deficit10 / deficit100 - 10.0) <= 1.0);
}

// Test 5: a glued disc whose joints are all broken at t = 0 gives the same history, bit for bit,
// as the same blocks never bonded (real joints only).
BOOST_AUTO_TEST_CASE(pre_broken_equals_never_bonded) {
  const meshes::Mesh mesh = make_ring_disc_mesh(0.1, 400);
  const scene::Scene sc = make_impact_scene(3.5, 1.0);
  EngineOptions bonded;
  Engine a(sc, mesh, bonded);
  BOOST_REQUIRE(!a.blocks().joints.empty());
  for (Joint& j : a.blocks().joints) j.broken = true;
  EngineOptions plain;
  plain.bond_virtual_joints = false;
  Engine b(sc, mesh, plain);
  BOOST_REQUIRE(b.blocks().joints.empty());
  int sliding_steps = 0;
  for (int k = 0; k < 150; ++k) {
    const StepReport ra = a.step(), rb = b.step();
    BOOST_REQUIRE_EQUAL(ra.time, rb.time);
    BOOST_REQUIRE_EQUAL(ra.dt, rb.dt);
    BOOST_REQUIRE_EQUAL(ra.open_close, rb.open_close);
    BOOST_REQUIRE_EQUAL(ra.cg_iterations, rb.cg_iterations);
    BOOST_REQUIRE_EQUAL(ra.contacts, rb.contacts);
    BOOST_REQUIRE_EQUAL(ra.closed, rb.closed);
    BOOST_REQUIRE_EQUAL(ra.energy.kinetic, rb.energy.kinetic);
    BOOST_REQUIRE_EQUAL(ra.energy.strain, rb.energy.strain);
    BOOST_REQUIRE_EQUAL(ra.max_penetration, rb.max_penetration);
    if (ra.sliding > 0) ++sliding_steps;
  }
  BOOST_TEST(a.blocks().vx == b.blocks().vx);
  BOOST_TEST(a.blocks().vy == b.blocks().vy);
  BOOST_TEST(a.crack_counts().total == 0);
  BOOST_TEST_MESSAGE("150 steps identical; steps with sliding contacts: " << sliding_steps);
}

// Gauges report the block that holds the point at t = 0; a point in no block is refused by name.
BOOST_AUTO_TEST_CASE(gauges_find_their_block_or_fail_clearly) {
  const double h = 0.01;
  scene::Scene sc = joint_scene(1e-6, 1e10, 1e6, 1e6, 30.0);
  sc.gauges.push_back({"left", {0.25 * h, 0.5 * h}});
  sc.gauges.push_back({"right", {1.75 * h, 0.5 * h}});
  Engine e(sc, two_squares(h));
  BOOST_TEST(e.gauge_blocks() == std::vector<Index>({0, 1}), boost::test_tools::per_element());
  sc.gauges.push_back({"outside", {3.0 * h, 0.5 * h}});
  BOOST_CHECK_EXCEPTION(Engine(sc, two_squares(h)), std::invalid_argument, [](const std::invalid_argument& error) {
    return std::string(error.what()).find("gauge 'outside'") != std::string::npos;
  });
}

// --- Cohesion and tension of real joints (issue 3) ------------------------------------------
// Two squares whose shared edge is a real joint closed at t = 0 (not bonded: no fracture check).
// The joint face is carried by one vertex-edge contact at each end of the edge, each with half the
// face (l_c = h/2), so the pair holds a tension σt·h and a shear c·h + f_n·tanφ, and after its
// first failure friction only.
namespace {

struct PairForce {
  double tension = 0.0;  // N/m, Σ −f_n over the pair's closed contacts
  double shear = 0.0;    // N/m, Σ |f_s|
  double compression = 0.0;
  int cohesive = 0;
};

PairForce pair_force(const Engine& e) {
  PairForce f;
  for (const Contact& c : e.contacts().contacts) {
    if (c.cohesive) ++f.cohesive;
    if (c.state == ContactState::Open) continue;
    f.tension -= c.normal_force;
    f.compression += std::max(0.0, c.normal_force);
    f.shear += std::abs(c.shear_force);
  }
  return f;
}

Engine cohesive_pair(double h, double tensile, double cohesion, double phi_deg, double vx, double vy) {
  scene::Scene sc = joint_scene(1e-6, 1e10, 1e7, 1e7, 30.0);
  scene::JointSet& real = sc.joint_sets[1];
  real.tensile_strength = tensile;
  real.cohesion = cohesion;
  real.friction_angle = phi_deg * kPi / 180.0;
  EngineOptions opt;
  opt.bond_virtual_joints = false;
  hold(opt.anchors, 0, {{0, 0}, {0, h}}, 0.0, 0.0);
  hold(opt.anchors, 1, {{2 * h, 0}, {2 * h, h}}, vx, vy);
  return Engine(sc, two_squares(h), opt);
}

}  // namespace

// Pulled apart: the pair carries tension up to σt·h (within one step's force increment) and none
// once it has failed; both contacts lose their cohesion together.
BOOST_AUTO_TEST_CASE(real_joint_holds_tension_up_to_its_strength) {
  const double h = 0.01, sigma_t = 1e6;
  Engine e = cohesive_pair(h, sigma_t, 1e7, 30.0, 0.01, 0.0);
  e.step();
  BOOST_TEST_REQUIRE(pair_force(e).cohesive == 2);
  BOOST_TEST(e.active_terms().cohesion);
  double peak = 0.0, increment = 0.0, previous = 0.0;
  int failed_at = -1;
  for (int k = 2; k <= 5000 && failed_at < 0; ++k) {
    e.step();
    const PairForce f = pair_force(e);
    if (f.cohesive == 0)
      failed_at = k;
    else {
      increment = f.tension - previous;
      previous = f.tension;
      peak = std::max(peak, f.tension);
    }
  }
  BOOST_TEST_MESSAGE("cohesive tension: peak " << peak << " N/m vs σt·h " << sigma_t * h << " N/m, increment "
                                               << increment << " N/m, failed at step " << failed_at);
  BOOST_TEST_REQUIRE(failed_at > 1);
  BOOST_TEST(peak <= sigma_t * h);
  BOOST_TEST(peak >= sigma_t * h - increment);
  BOOST_TEST(increment < 0.05 * sigma_t * h);
  BOOST_TEST(e.statistics().cohesion_failures == 2);
  for (int k = 0; k < 20; ++k) e.step();
  BOOST_TEST(pair_force(e).tension <= 0.0);
}

// Pushed together and slid: the shear carried peaks at c·h + f_n·tanφ; once cohesion is lost
// the shear never exceeds the friction f_n·tanφ again (the stress drop sets off a stick-slip
// oscillation, so it is not constant), and every sliding contact sits at it.
BOOST_AUTO_TEST_CASE(real_joint_holds_shear_up_to_cohesion_plus_friction) {
  const double h = 0.01, cohesion = 1e6, phi = 20.0;
  const double tan_phi = std::tan(phi * kPi / 180.0);
  Engine e = cohesive_pair(h, 1e5, cohesion, phi, -0.01, 0.02);
  double worst_excess = -1e300, peak_ratio = 0.0;
  int failed_at = -1;
  for (int k = 1; k <= 5000 && failed_at < 0; ++k) {
    e.step();
    const PairForce f = pair_force(e);
    if (f.cohesive == 0) {
      failed_at = k;
      break;
    }
    const double limit = cohesion * h + f.compression * tan_phi;
    worst_excess = std::max(worst_excess, f.shear - limit);
    peak_ratio = std::max(peak_ratio, f.shear / limit);
  }
  double friction_excess = 0.0, sliding_error = 0.0;
  int sliding_steps = 0;
  for (int k = 0; k < 2000; ++k) {
    e.step();
    for (const Contact& c : e.contacts().contacts) {
      if (c.state == ContactState::Open) continue;
      const double friction = c.normal_force * tan_phi;
      friction_excess = std::max(friction_excess, std::abs(c.shear_force) - friction);
      if (c.state == ContactState::Sliding) {
        ++sliding_steps;
        sliding_error = std::max(sliding_error, std::abs(std::abs(c.shear_force) - friction) / friction);
      }
    }
  }
  BOOST_TEST_MESSAGE("cohesive shear: failed at step " << failed_at << ", peak |f_s|/limit " << peak_ratio
                                                       << "; after: largest |f_s| - f_n·tanφ " << friction_excess
                                                       << " N/m, " << sliding_steps << " sliding contact-steps within "
                                                       << sliding_error);
  BOOST_TEST_REQUIRE(failed_at > 1);
  BOOST_TEST(worst_excess <= 0.0);
  BOOST_TEST(peak_ratio >= 0.95);  // the shear did build up to the limit before failing
  BOOST_TEST(e.statistics().cohesion_failures == 2);
  // Locked contacts may exceed friction only by the open-close hysteresis band ks·tol (tol =
  // state_tolerance × the allowed step displacement; 100 N/m here, 2% of the friction).
  const double band = 0.4 * 1e10 * e.options().state_tolerance * e.allowed_displacement();
  BOOST_TEST(friction_excess <= band);
  BOOST_TEST(sliding_steps > 0);
  BOOST_TEST(sliding_error <= 1e-9);
}

namespace {

/// Two squares of two_squares, the left one held, the right one's far corners driven at
/// (vx_bottom, vy) and (vx_top, vy) m/s: different x speeds turn the right square a little, so
/// that once the joint has broken the vertex–vertex rule judges both corners on the left square's
/// edge (the entrance line with the larger gap, docs/design.md §4.1), the right square's vertices
/// against it: each corner's contact swaps vertex and edge in the step after the break.
struct SwappingBreak {
  const char* name;
  double tensile_strength, cohesion;  // Pa, of the virtual joint
  double vx_bottom, vx_top, vy;       // m/s
  CrackType type;
  bool corners_stay_closed;
  // Shear softening (JointSet::shear_fracture_energy, J/m²): the joint slides by δc before it
  // breaks, farther than the vertex-vertex capture radius, so that the corner loaded in
  // compression swaps as two vertex-edge contacts instead (docs/design.md §4.7).
  std::optional<double> shear_fracture_energy = std::nullopt;
  bool swaps_as_vertex_vertex = true;  // else as two vertex-edge contacts
  int corners_swapped = 2;             // corners whose contact the right square's vertex holds after the break
};
}  // namespace

// A joint that breaks hands its corners to ordinary contacts, and each corner's contact carries
// its own spring, state and stored energy into the step after the break, where the ledger books
// what the break released: what opens or slides off is released once, what stays closed stays
// stored. When both corners' contacts swap vertex and edge, each block's vertices are the ends
// of the other's edge; matching a swapped corner by either end of its edge once gave both new
// contacts the state of the first corner, so the second corner's spring was booked as released
// while it stayed loaded and the first's was booked twice: the ledger's residual jumped at the
// break by 27% (shear) and 98% (tension) of the energy the joint stored, to balance errors of
// 3.2% and 11.9%.
// A joint softened in shear slides δc ≈ 50 µm before it breaks (2·G_IIf/τ), and its compressed
// corner is then the right square's vertex on the left square's edge, a vertex-edge contact
// like the held one, with vertex and edge swapped. Matched only as vertex-vertex corners, it came
// in new, and its spring of ½·kn·d² with it: the residual jumped by 97.5% of the joint's energy
// (balance error 0.63%). Carried, the spring moved to the other copy of the node, δc along the
// joint, where the squares' relative turn leaves it 1% less overlap: the residual moved by 1.8%
// of the joint's energy, and by 0.03% in the unsoftened shear case. A broken joint's swapped
// corner now keeps its compression (keep_normal_spring, docs/design.md §4.7), and what remains is the
// linearised step's own error (§9): the residual moves at the break by 1.3e-7 (softened), 1.3e-6
// (shear) and 1.3e-5 (tension) of the joint's stored energy, and the balance error stays below
// 5e-5. The checks allow 1e-4 of the joint's energy, under the 3e-4 and 1.8e-2 that moving the
// spring to the other copy cost, and a balance error of 1e-3.
BOOST_AUTO_TEST_CASE(the_ledger_closes_when_a_broken_joints_corners_swap_vertex_and_edge) {
  const double h = 0.01, phi_virtual = 30.0, phi_real = 20.0;
  const double jump_tolerance = 1e-4;  // of the joint's stored energy (the test's comment)
  const SwappingBreak cases[] = {
      {"shear under compression", 1e7, 1e6, -0.012, -0.008, 0.02, CrackType::Shear, true},
      {"tension", 1e6, 1e7, 0.012, 0.008, 0.0, CrackType::Tensile, false},
      {"shear under compression, softened", 1e7, 1e6, -0.0012, -0.0008, 0.02, CrackType::Shear, true, 100.0, false, 1},
  };
  for (const SwappingBreak& k : cases) {
    scene::Scene sc = joint_scene(1e-6, 1e10, k.tensile_strength, k.cohesion, phi_virtual);
    sc.joint_sets[1].friction_angle = phi_real * kPi / 180.0;  // the broken joint keeps friction
    sc.joint_sets[0].shear_fracture_energy = k.shear_fracture_energy;
    // A small allowed step, and with it a capture radius (the search distance) of 12.5 µm, well
    // below the slip at which the softened joint breaks (2·G_IIf/τ ≈ 50 µm).
    if (k.shear_fracture_energy) sc.analysis.max_displacement_ratio = 5e-4;
    EngineOptions opt;
    hold(opt.anchors, 0, {{0, 0}, {0, h}}, 0.0, 0.0);
    hold(opt.anchors, 1, {{2 * h, 0}}, k.vx_bottom, k.vy);
    hold(opt.anchors, 1, {{2 * h, h}}, k.vx_top, k.vy);
    Engine e(sc, two_squares(h), opt);
    const int max_steps = 20000, steps_after = 200;
    int step = 1;
    while (step <= max_steps && e.step().new_cracks == 0) ++step;
    BOOST_REQUIRE_MESSAGE(step <= max_steps, k.name << ": the joint did not break");
    BOOST_REQUIRE_EQUAL(e.cracks().size(), 1u);
    BOOST_TEST(static_cast<int>(e.cracks()[0].type) == static_cast<int>(k.type), k.name);
    double joint_energy = 0.0, smallest_corner = 1e300;
    for (const Contact& c : e.contacts().contacts)
      if (c.joint == 0) {
        joint_energy += c.stored_normal + c.stored_shear;
        smallest_corner = std::min(smallest_corner, c.stored_normal + c.stored_shear);
      }
    const double before = e.ledger().residual();
    e.step();  // the break takes effect: its contacts are ordinary ones from here on
    const double jump = e.ledger().residual() - before;
    int swapped = 0, closed = 0;
    for (const Contact& c : e.contacts().contacts) {
      swapped += c.vblock == 1 && (c.vertex_vertex || !k.swaps_as_vertex_vertex);
      closed += c.state != ContactState::Open;
    }
    for (int s = 1; s < steps_after; ++s) e.step();
    const EnergyLedger& l = e.ledger();
    BOOST_TEST_MESSAGE(k.name << ": break at step " << step << ", joint stored " << joint_energy
                              << " J/m (smallest corner " << smallest_corner << "), residual jump " << jump
                              << " J/m, released by the break " << l.total.joint_breaks << ", friction "
                              << l.total.friction << ", largest balance error " << l.largest_balance_error);
    BOOST_TEST(swapped == k.corners_swapped, k.name << ": corners swapped vertex and edge (the case this test is for)");
    BOOST_TEST((closed == 2) == k.corners_stay_closed, k.name);
    BOOST_TEST(std::abs(jump) <= jump_tolerance * joint_energy, k.name);
    BOOST_TEST(l.largest_balance_error <= 1e-3, k.name);
  }
}

namespace {

/// Which way a test drives the joint of two_squares: pulled apart (along x, mode I) or slid along
/// it (along y, mode II).
enum class Drive { Pull, Slide };

/// Mean displacement of the right block's copies of the joint's two nodes from the left block's,
/// along x (the opening) or along y (the slip) (m).
double separation_of_two_squares(const BlockSystem& b, Drive drive) {
  const std::vector<double>& coordinate = drive == Drive::Pull ? b.vx : b.vy;
  double sum = 0.0;
  int copies = 0;
  for (std::size_t v = 0; v < b.vx.size(); ++v) {
    const meshes::Index node = b.vertex_node[v];
    if (node != 1 && node != 4) continue;  // the nodes at x = h
    const bool right = static_cast<Index>(v) >= b.begin(1);
    sum += right ? coordinate[v] : -coordinate[v];
    ++copies;
  }
  BOOST_REQUIRE_EQUAL(copies, 4);
  return sum / 2.0;
}

/// The softening law a driven joint of two_squares follows: its strength (N/m), the separation at
/// the peak δ0 (two springs of the drive's stiffness) and the one at which the force is spent,
/// δc = 2·G/s, from the set's fracture energy of that mode (m).
struct SofteningLaw {
  double strength = 0.0, peak = 0.0, spent = 0.0;
  double force(double separation) const { return strength * (spent - separation) / (spent - peak); }
};
SofteningLaw law_of(const scene::JointSet& js, double h, Drive drive) {
  const bool pull = drive == Drive::Pull;
  const double stress = pull ? js.tensile_strength : js.cohesion;  // Pa; sliding under no normal load
  const double energy = pull ? js.fracture_energy : js.shear_fracture_energy.value_or(js.fracture_energy);
  const double stiffness = 2.0 * (pull ? js.normal_stiffness : js.shear_stiffness);
  return {stress * h, stress * h / stiffness, 2.0 * energy / stress};
}

/// What a driven joint of two_squares did until it broke (at most max_steps steps).
struct SofteningRun {
  int break_step = -1;
  double peak = 0.0;                   // largest force of the drive's mode, N/m
  double worst_softening_error = 0.0;  // largest |f − f_law(δ)| on the softening branch, N/m
  double separation_at_break = 0.0;    // m
  CrackType failure = CrackType::None;
  double dissipated = 0.0;             // the ledger's joint breaks after the break took effect, J/m
  double largest_balance_error = 0.0;
  std::vector<double> forces;  // force of the drive's mode per step, N/m
};

/// Steps an engine whose joint broke in its last step until the break has taken effect (the
/// joint's contacts carried on or opened).
void let_the_break_take_effect(Engine& e) {
  for (int k = 0; k < 5; ++k) e.step();
}

SofteningRun drive_until_broken(const scene::Scene& sc, double h, Drive drive, double speed, int max_steps) {
  const bool pull = drive == Drive::Pull;
  Engine e = right_square_driven(sc, h, pull ? speed : 0.0, pull ? 0.0 : speed);
  const SofteningLaw law = law_of(sc.joint_sets[0], h, drive);
  SofteningRun r;
  for (int k = 1; k <= max_steps; ++k) {
    const StepReport rep = e.step();
    const JointForce jf = e.joint_forces().at(0);
    const double f = pull ? jf.normal : std::abs(jf.shear);
    const double separation = std::abs(separation_of_two_squares(e.blocks(), drive));
    if (rep.new_cracks > 0) {
      r.break_step = k;
      r.separation_at_break = separation;
      r.failure = e.blocks().joints[0].failure;
      break;
    }
    r.forces.push_back(f);
    r.peak = std::max(r.peak, f);
    if (e.blocks().joints[0].damage > 0.0 && separation < law.spent)
      r.worst_softening_error = std::max(r.worst_softening_error, std::abs(f - law.force(separation)));
  }
  let_the_break_take_effect(e);
  r.dissipated = e.ledger().total.joint_breaks;
  r.largest_balance_error = e.ledger().largest_balance_error;
  return r;
}

SofteningRun pull_until_broken(const scene::Scene& sc, double h, double speed, int max_steps) {
  return drive_until_broken(sc, h, Drive::Pull, speed, max_steps);
}

/// A joint of two_squares driven at `speed` (and again at half of it) until it broke, each step
/// `dt`, checked against its softening law (law_of). One step's increment of the elastic branch,
/// 2·k·speed·dt (k the drive's spring): the fracture check lets a joint carry at most that beyond
/// its strength before it softens, as a brittle joint before it breaks; the forces after each
/// check lie on the law. The damage is updated after each step, so within a step the springs keep
/// the last step's stiffness: the joint takes up to the peak's increment and, on the falling
/// branch, about (f/δ)·Δδ more than the law while it separates by Δδ = speed·dt. The work beyond
/// G·l is then at most Δδ·s·l·(1 + ln μ), and it halves with Δδ. Returns the run at `speed`.
SofteningRun expect_on_its_softening_law(const scene::Scene& sc, double h, Drive drive, double speed, double dt) {
  const SofteningRun r = drive_until_broken(sc, h, drive, speed, 10000);
  const SofteningRun half = drive_until_broken(sc, h, drive, 0.5 * speed, 20000);
  BOOST_REQUIRE(r.break_step > 0 && half.break_step > 0);
  const scene::JointSet& js = sc.joint_sets[0];
  const SofteningLaw law = law_of(js, h, drive);
  const double spring = drive == Drive::Pull ? js.normal_stiffness : js.shear_stiffness;
  const double elastic_increment = 2.0 * spring * speed * dt, separation_step = speed * dt;
  const double fracture_work = 0.5 * law.strength * law.spent;  // G·l
  const double lag_bound = separation_step * law.strength * (1.0 + std::log(law.spent / law.peak));
  const double excess = r.dissipated - fracture_work, excess_half = half.dissipated - fracture_work;
  BOOST_TEST_MESSAGE((drive == Drive::Pull ? "pulled" : "slid")
                     << ": peak " << r.peak << " N/m against the strength " << law.strength << ", largest error on "
                     << "the softening branch " << r.worst_softening_error << " N/m, break at step " << r.break_step
                     << " at separation " << r.separation_at_break << " m (δc " << law.spent << "), dissipated "
                     << r.dissipated << " J/m against G·l " << fracture_work << " (" << excess / fracture_work
                     << "; at half the speed " << excess_half / fracture_work << ", bound " << lag_bound / fracture_work
                     << "), largest balance error " << r.largest_balance_error);
  BOOST_TEST(r.peak <= law.strength);
  BOOST_TEST(r.peak >= law.strength - elastic_increment);
  BOOST_TEST(r.worst_softening_error <= 1e-6 * law.strength);
  BOOST_TEST(std::abs(r.separation_at_break - law.spent) <= 2.0 * separation_step);
  BOOST_TEST(excess >= 0.0);
  BOOST_TEST(excess <= lag_bound);
  BOOST_TEST(excess_half >= 0.0);
  BOOST_TEST(excess_half <= 0.6 * excess);  // first order in the step's separation
  BOOST_TEST(r.largest_balance_error <= 1e-4);
  return r;
}

}  // namespace

// Softening (JointSet::fracture_energy): pulled apart slowly, the joint carries σt·l at the
// opening δ0 = σt·l/(2·kn) (50 steps of pulling here), then a force falling linearly to zero at
// δc = 2·G_f/σt, and breaks there having dissipated G_f·l, whatever its springs held at the peak
// (½·σt·l·δ0, a tenth of it here).
BOOST_AUTO_TEST_CASE(a_softening_joint_dissipates_its_fracture_energy) {
  const double h = 0.01, sigma_t = 1e6, kn = 1e10, dt = 1e-6;
  scene::Scene sc = joint_scene(dt, kn, sigma_t, 1e7, 30.0);
  const double ductility = 10.0;                                                // μ = δc/δ0
  const double peak_opening = sigma_t * h / (2.0 * kn);                         // δ0
  sc.joint_sets[0].fracture_energy = 0.5 * sigma_t * ductility * peak_opening;  // G_f = ½·σt·δc
  const SofteningRun r = expect_on_its_softening_law(sc, h, Drive::Pull, 0.01, dt);
  BOOST_TEST(static_cast<int>(r.failure) == static_cast<int>(CrackType::Tensile));
}

// Mode II on its own law (JointSet::shear_fracture_energy): slid along the joint with no normal
// load, the joint carries c·l at the slip δ0 = c·l/(2·ks), then a shear force falling linearly to
// zero at δc = 2·G_IIf/c, and breaks there in shear having dissipated G_IIf·l; tension stays
// brittle (fracture_energy 0).
BOOST_AUTO_TEST_CASE(a_joint_softening_in_shear_dissipates_its_shear_fracture_energy) {
  const double h = 0.01, cohesion = 1e6, kn = 1e10, dt = 1e-6;
  // No friction: the strength is c·l whatever normal force the sliding block's small turn makes.
  scene::Scene sc = joint_scene(dt, kn, 1e7, cohesion, 0.0);
  scene::JointSet& js = sc.joint_sets[0];
  const double ductility = 10.0;                                       // μ = δc/δ0
  const double peak_slip = cohesion * h / (2.0 * js.shear_stiffness);  // δ0
  js.shear_fracture_energy = 0.5 * cohesion * ductility * peak_slip;   // G_IIf = ½·c·δc
  const SofteningRun r = expect_on_its_softening_law(sc, h, Drive::Slide, 0.01, dt);
  BOOST_TEST(static_cast<int>(r.failure) == static_cast<int>(CrackType::Shear));
  // Without a shear energy of its own the same joint is brittle in shear here (its G_f is 0): it
  // breaks at its strength, at the slip δ0 instead of δc.
  js.shear_fracture_energy.reset();
  const SofteningRun brittle = drive_until_broken(sc, h, Drive::Slide, 0.01, 5000);
  BOOST_REQUIRE(brittle.break_step > 0);
  BOOST_TEST(std::abs(brittle.separation_at_break - peak_slip) <= 2.0 * 0.01 * dt);
}

// Softening keeps friction (Contact::damaged_ks, docs/design.md §5): pushed in and slid along,
// a joint softening in shear carries (1 − D)·ks·s on its intact part and, on its damaged part,
// Coulomb friction up to D·tanφ·f_n. The intact part's law starts at the strength c·l + f_n·tanφ,
// above the friction f_n·tanφ, so the shear force |f_s| never falls below f_n·tanφ while the joint
// softens, and at the break, where D reaches 1, it is that friction: the broken joint's corners
// slide on from it (same φ) without a jump. A law that softened the whole spring let |f_s| fall
// to (1 − D)·ks·s, 25% of the friction in the step before the break here, and jump back to the
// friction after it. Checked: |f_s| ≥ f_n·tanφ on the softening branch, to 1e-6 of c·l (the
// joint's force is two contacts' projected on the joint, exact to round-off while the right
// square barely turns); |f_s| in the step before the break within two steps' fall of the law
// of f_n·tanφ (the damage follows the slip a step behind, so the intact part still carries up
// to a step's fall when the joint breaks), and in the step after it sliding at f_n·tanφ, as
// close to the force before; the ledger closing to 1e-4, and friction dissipated before the break.
BOOST_AUTO_TEST_CASE(a_joint_softening_under_compression_keeps_its_friction) {
  const double h = 0.01, cohesion = 1e6, phi = 30.0, kn = 1e10, dt = 1e-6;
  const double push = 0.003, slide = 0.02;  // m/s
  scene::Scene sc = joint_scene(dt, kn, 1e7, cohesion, phi);
  sc.joint_sets[0].shear_fracture_energy = 5.0;         // J/m²: δc ≈ 10·δ0 here
  sc.joint_sets[1].friction_angle = phi * kPi / 180.0;  // the broken joint keeps the same friction
  const double tan_phi = std::tan(phi * kPi / 180.0);
  Engine e = right_square_driven(sc, h, -push, slide);
  double least_margin = 1e300, friction_before_break = 0.0;  // N/m, J/m
  JointForce before;
  int break_step = -1, softening_steps = 0;
  for (int k = 1; k <= 5000 && break_step < 0; ++k) {
    const StepReport rep = e.step();
    const JointForce f = e.joint_forces().at(0);
    if (rep.new_cracks > 0) {
      break_step = k;
      break;
    }
    if (e.blocks().joints[0].damage > 0.0) {
      ++softening_steps;
      least_margin = std::min(least_margin, std::abs(f.shear) + f.normal * tan_phi);  // f.normal < 0
    }
    before = f;
    friction_before_break = e.ledger().total.friction;
  }
  BOOST_REQUIRE_MESSAGE(break_step > 0, "the joint did not break");
  BOOST_REQUIRE(softening_steps > 20);
  BOOST_REQUIRE_EQUAL(e.cracks().size(), 1u);
  BOOST_TEST(static_cast<int>(e.cracks()[0].type) == static_cast<int>(CrackType::Shear));
  const double friction_at_break = -before.normal * tan_phi;
  const double law_step = (cohesion * h + friction_at_break) / softening_steps;  // N/m, the law's mean fall per step
  e.step();                                                                      // the break takes effect
  const JointForce after = e.joint_forces().at(0);
  const double after_ratio = std::abs(after.shear) / (-after.normal * tan_phi);
  BOOST_TEST_MESSAGE("softening under compression: "
                     << softening_steps << " steps, break at step " << break_step << ", least |f_s| − f_n·tanφ "
                     << least_margin << " N/m, |f_s| " << std::abs(before.shear)
                     << " N/m before the break against f_n·tanφ " << friction_at_break << " (law's fall per step "
                     << law_step << "), after it " << std::abs(after.shear) << ", " << after_ratio
                     << " of f_n·tanφ; friction dissipated before the break " << friction_before_break
                     << " J/m, largest balance error " << e.ledger().largest_balance_error);
  BOOST_TEST(before.normal < 0.0);  // under compression
  BOOST_TEST(least_margin >= -1e-6 * cohesion * h);
  BOOST_TEST(std::abs(std::abs(before.shear) - friction_at_break) <= 2.0 * law_step);
  BOOST_TEST(std::abs(after_ratio - 1.0) <= 1e-6);
  BOOST_TEST(std::abs(std::abs(after.shear) - std::abs(before.shear)) <= 2.0 * law_step);
  BOOST_TEST(friction_before_break > 0.0);
  BOOST_TEST(e.ledger().largest_balance_error <= 1e-4);
}

namespace {

/// What a joint of two_squares, pushed in and then slid along at a fixed normal position, spent
/// until it broke in shear.
struct CompressedSlide {
  int break_step = -1, softening_steps = 0;
  double normal = 0.0;                 // mean normal force over the softening, N/m (negative: compression)
  double normal_spread = 0.0;          // largest |f_n − mean| over the softening, N/m
  double slip_at_break = 0.0;          // slip in the step before the break, m
  double joint_breaks = 0.0;           // the ledger's joint breaks once the break took effect, J/m
  double friction_before_break = 0.0;  // the ledger's friction in the step before the break, J/m
  double largest_balance_error = 0.0;
};

/// two_squares with the left square held and the right one pushed in at `push` (m/s) for
/// `push_steps` steps.
Engine pushed_in(const scene::Scene& sc, double h, double push, int push_steps) {
  Engine e = right_square_driven(sc, h, -push, 0.0);
  for (int k = 0; k < push_steps; ++k) e.step();
  return e;
}

/// Pushes the right square of two_squares in (pushed_in), then holds its normal position (its
/// anchors' targets stop where they are) and slides it along the joint at `slide` (m/s) until the
/// joint breaks (at most max_steps).
CompressedSlide slide_under_compression(const scene::Scene& sc, double h, double push, int push_steps, double slide,
                                        int max_steps) {
  Engine e = pushed_in(sc, h, push, push_steps);
  CompressedSlide r;
  for (Anchor& a : e.blocks().anchors) {
    if (a.block != 1) continue;
    a.x_start += a.vx * e.time();  // the targets go on from where the push left them
    a.vx = 0.0;
    a.y_start -= slide * e.time();
    a.vy = slide;
  }
  double normal_sum = 0.0, normal_low = 1e300, normal_high = -1e300;
  for (int k = 1; k <= max_steps; ++k) {
    const StepReport rep = e.step();
    if (rep.new_cracks > 0) {
      r.break_step = k;
      break;
    }
    const JointForce f = e.joint_forces().at(0);
    const double slip = std::abs(separation_of_two_squares(e.blocks(), Drive::Slide));
    if (e.blocks().joints[0].damage > 0.0) {
      ++r.softening_steps;
      normal_sum += f.normal;
      normal_low = std::min(normal_low, f.normal);
      normal_high = std::max(normal_high, f.normal);
    }
    r.slip_at_break = slip;
    r.friction_before_break = e.ledger().total.friction;
  }
  BOOST_REQUIRE_MESSAGE(r.break_step > 0, "the joint did not break");
  r.normal = r.softening_steps > 0 ? normal_sum / r.softening_steps : 0.0;
  r.normal_spread = r.softening_steps == 0 ? 0.0 : std::max(normal_high - r.normal, r.normal - normal_low);
  let_the_break_take_effect(e);
  r.joint_breaks = e.ledger().total.joint_breaks;
  r.largest_balance_error = e.ledger().largest_balance_error;
  return r;
}

}  // namespace

// How a joint softening under compression spends its energy (docs/design.md §5, §9): at a fixed
// compression f_n the intact part follows the shear law from τ·l = c·l + f_n·tanφ at δ0 = τ·l/K_s
// to zero at δc = 2·G_IIf/τ (K_s the two contacts' ks), so the damage takes G_IIf·l from it. The
// damaged part slides at its friction limit D·f_n·tanφ from the onset, a slip δf = f_n·tanφ/K_s
// behind the joint, so each share that joins it keeps ½·dD·K_s·δf² and the joint breaks
// release G_IIf·l − ½·(f_n·tanφ)²/K_s; the rest stays in the part's spring and goes on with the
// broken joint's corners. Its sliding dissipates ∫ D·f_n·tanφ ds to the break, with the secant
// damage of the linear law D(x) = 1 − (μ − x)/(x·(μ − 1)), x = s/δ0:
//   f_n·tanφ·δ0·[(μ − 1) − (μ·ln μ − μ + 1)/(μ − 1)].
// Both in the continuum limit. The damage follows the slip a step behind, so the breaks take up to
// the softening tests' lag bound Δs·τ·l·(1 + ln μ) more (Δs the slip per step), and the part slides
// with the last step's damage and the breaking step's sliding is not counted, so the friction
// comes about two steps' sliding f_n·tanφ·Δs short (1.6–1.9 steps from Δs = 20 nm to 2.5 nm);
// both first order, checked at half the slip per step. The compression (f_n·tanφ a quarter of c·l
// here) moves as the right square turns a little; checked within 1% of its mean, which the
// formulas use. Slid this slowly, the joint breaks a step before its damage reaches 1 and its
// corners stay stuck: the ledger closes only if the break releases the ½·D·(1 − D)·ks·s_p² the
// corner's one spring holds less than the joint's two parts (1.7e-4 balance error without it).
BOOST_AUTO_TEST_CASE(a_joint_softening_under_compression_spends_its_shear_fracture_energy_and_friction) {
  const double h = 0.01, cohesion = 1e6, phi = 30.0, kn = 1e10, dt = 1e-6;
  const double push = 0.01, slide = 0.005;  // m/s
  const int push_steps = 100;
  scene::Scene sc = joint_scene(dt, kn, 1e7, cohesion, phi);
  sc.joint_sets[1].friction_angle = phi * kPi / 180.0;
  const double tan_phi = std::tan(phi * kPi / 180.0), stiffness = 2.0 * sc.joint_sets[0].shear_stiffness;
  // G_IIf for a ductility μ = δc/δ0 = 10 at the compression the push gives.
  const double pushed = pushed_in(sc, h, push, push_steps).joint_forces().at(0).normal;  // N/m
  const double probe_strength = cohesion * h - pushed * tan_phi;
  const double ductility = 10.0;
  sc.joint_sets[0].shear_fracture_energy = 0.5 * ductility * probe_strength * probe_strength / (stiffness * h);
  const double G = *sc.joint_sets[0].shear_fracture_energy;

  struct Expected {
    double breaks, friction, lag_bound, friction_lag, spent;
  };
  auto expected = [&](const CompressedSlide& r, double slip_step) {
    const double friction_force = -r.normal * tan_phi;                         // N/m
    const double strength = cohesion * h + friction_force;                     // τ·l, N/m
    const double peak = strength / stiffness, spent = 2.0 * G * h / strength;  // δ0, δc (m)
    const double mu = spent / peak;
    const double integral_of_damage = (mu - 1.0) - (mu * std::log(mu) - mu + 1.0) / (mu - 1.0);  // ∫ D dx
    return Expected{G * h - 0.5 * friction_force * friction_force / stiffness,
                    friction_force * peak * integral_of_damage, slip_step * strength * (1.0 + std::log(mu)),
                    friction_force * slip_step, spent};
  };
  const CompressedSlide r = slide_under_compression(sc, h, push, push_steps, slide, 20000);
  const CompressedSlide half = slide_under_compression(sc, h, push, push_steps, 0.5 * slide, 40000);
  const Expected x = expected(r, slide * dt), x_half = expected(half, 0.5 * slide * dt);
  const double breaks_excess = r.joint_breaks - x.breaks, breaks_excess_half = half.joint_breaks - x_half.breaks;
  const double friction_error = r.friction_before_break - x.friction;
  const double friction_error_half = half.friction_before_break - x_half.friction;
  BOOST_TEST_MESSAGE("softening under compression f_n "
                     << r.normal << " N/m (spread " << r.normal_spread << "), G_IIf " << G << " J/m²: break at step "
                     << r.break_step << ", slip " << r.slip_at_break << " m (δc " << x.spent << "); joint breaks "
                     << r.joint_breaks << " J/m against " << x.breaks << " (excess " << breaks_excess
                     << ", at half the slip per step " << breaks_excess_half << ", bound " << x.lag_bound
                     << "); friction " << r.friction_before_break << " J/m against " << x.friction << " (error "
                     << friction_error << ", at half " << friction_error_half << ", a step's " << x.friction_lag
                     << "); largest balance error " << r.largest_balance_error);
  BOOST_REQUIRE(r.softening_steps > 20 && half.softening_steps > 40);
  BOOST_TEST(r.normal < 0.0);
  BOOST_TEST(r.normal_spread <= 0.01 * -r.normal);
  BOOST_TEST(std::abs(r.slip_at_break - x.spent) <= 2.0 * slide * dt);
  BOOST_TEST(breaks_excess >= 0.0);
  BOOST_TEST(breaks_excess <= x.lag_bound);
  BOOST_TEST(breaks_excess_half >= 0.0);
  BOOST_TEST(breaks_excess_half <= 0.6 * breaks_excess);
  BOOST_TEST(std::abs(friction_error) <= 2.5 * x.friction_lag);
  BOOST_TEST(std::abs(friction_error_half) <= 2.5 * x_half.friction_lag);
  BOOST_TEST(r.largest_balance_error <= 1e-4);
}

// A joint whose springs hold more than G_f·l at its strength (μ ≤ 1) cannot soften: it breaks
// in the same step as a brittle one, with the same forces on the way.
BOOST_AUTO_TEST_CASE(a_joint_holding_more_than_its_fracture_energy_breaks_at_its_strength) {
  const double h = 0.01, sigma_t = 1e6, kn = 1e10, speed = 0.01;
  scene::Scene brittle = joint_scene(1e-6, kn, sigma_t, 1e7, 30.0);
  scene::Scene stiff = brittle;
  stiff.joint_sets[0].fracture_energy = 0.5 * 0.5 * sigma_t * sigma_t * h / (2.0 * kn);  // μ = 0.5
  const SofteningRun a = pull_until_broken(brittle, h, speed, 5000), b = pull_until_broken(stiff, h, speed, 5000);
  BOOST_REQUIRE(a.break_step > 0);
  BOOST_TEST(a.break_step == b.break_step);
  BOOST_TEST(a.forces == b.forces, boost::test_tools::per_element());
}

namespace {

/// A failure ratio from which the mix of a loaded joint is measured: below it the first steps'
/// round-off and the square's settling in its anchors dominate.
constexpr double kLoadedRatio = 0.5;
/// How far the mix may move while the joint is loaded for the closed forms to hold: the right
/// square turns a little in its anchors as the joint softens (1.3–1.4% measured).
constexpr double kLargestMixChange = 0.02;

/// What a joint of two_squares pulled apart and slid at once did until it broke.
struct MixedRun {
  int break_step = -1;
  double peak_normal = 0.0;         // largest normal force, N/m
  double largest_mix_change = 0.0;  // largest |r1 − r2|/max(r1, r2) of the undamaged ratios, loaded
  double dissipated = 0.0;          // the ledger's joint breaks after the break took effect, J/m
  double largest_balance_error = 0.0;
};

/// The right square of two_squares driven at (pull, slide) m/s until its joint broke (at most
/// max_steps steps); the ratios r1 = f_n/(σt·l) and r2 = |f_s|/(c·l) of the undamaged forces.
MixedRun pull_and_slide_until_broken(const scene::Scene& sc, double h, double pull, double slide, int max_steps) {
  Engine e = right_square_driven(sc, h, pull, slide);
  const scene::JointSet& js = sc.joint_sets[0];
  MixedRun r;
  for (int k = 1; k <= max_steps; ++k) {
    if (e.step().new_cracks > 0) {
      r.break_step = k;
      break;
    }
    const JointForce f = e.joint_forces().at(0);
    r.peak_normal = std::max(r.peak_normal, f.normal);
    const double r1 = f.normal_undamaged / (js.tensile_strength * h);
    const double r2 = std::abs(f.shear_undamaged) / (js.cohesion * h);
    if (std::max(r1, r2) >= kLoadedRatio)
      r.largest_mix_change = std::max(r.largest_mix_change, std::abs(r1 - r2) / std::max(r1, r2));
  }
  let_the_break_take_effect(e);
  r.dissipated = e.ledger().total.joint_breaks;
  r.largest_balance_error = e.ledger().largest_balance_error;
  return r;
}

}  // namespace

// Both modes at once (JointSet::mode_interaction): pulled apart and slid in proportion, so that
// the tension's and the shear's failure ratios stay equal (r1 = r2: the mix cos²α = sin²α = ½),
// with c = σt and no friction. Without interaction both springs soften on the one drive
// x = r1 = r2, and the joint dissipates all of both modes' energies: G_f·l in tension and
// G_II·l = G_f·l·kn/ks in shear (the tension's μ on the shear springs). Combined, the drive is
// √(r1² + r2²): the joint starts softening at r1 = r2 = 1/√2 (its normal force σt·l/√2) and
// dissipates half of each, cos²α·(μ/μ_I)·G_f·l + sin²α·(μ/μ_II)·G_IIf·l with μ the harmonic mix
// of the modes' μ_I and μ_II, which meets G_I/G_f + G_II/G_IIf = 1; with a shear energy of its
// own, G_IIf·l = 2·G_II·l here (μ_II = 2·μ_I, μ = 4/3·μ_I), two thirds of each. The damage lags a
// step as in the single-mode tests: the work beyond the closed form is within the sum of the two
// modes' lag bounds, Δδ·s·l·(1 + ln μ) each, and halves with the step. The peak normal force may
// exceed the onset's by the mix's change (the square turns a little: r1/r2 moves by up to 1.4%).
BOOST_AUTO_TEST_CASE(a_joint_softening_in_both_modes_at_once_dissipates_the_mixed_mode_energy) {
  const double h = 0.01, strength = 1e6, kn = 1e10, dt = 1e-6, ductility = 10.0;  // μ_I
  scene::Scene sc = joint_scene(dt, kn, strength, strength, 0.0);
  scene::JointSet& js = sc.joint_sets[0];
  js.fracture_energy = 0.5 * strength * ductility * strength * h / (2.0 * kn);            // G_f = ½·σt·δc
  const double pull = 0.01, slide = pull * js.normal_stiffness / js.shear_stiffness;      // m/s: r1 = r2
  const double tension_energy = js.fracture_energy * h;                                   // G_f·l, J/m
  const double shear_energy = tension_energy * js.normal_stiffness / js.shear_stiffness;  // G_II·l
  const double opening_step = pull * dt, slip_step = slide * dt;
  const double lag_bound = (opening_step + slip_step) * strength * h * (1.0 + std::log(2.0 * ductility));

  struct Case {
    const char* name;
    scene::ModeInteraction interaction;
    std::optional<double> shear_fracture_energy;  // J/m²
    double expected;                              // J/m
    double onset;                                 // normal force at the onset, N/m
  };
  const Case cases[] = {
      {"none", scene::ModeInteraction::None, std::nullopt, tension_energy + shear_energy, strength * h},
      {"quadratic", scene::ModeInteraction::Quadratic, std::nullopt, 0.5 * (tension_energy + shear_energy),
       strength * h / std::sqrt(2.0)},
      {"quadratic, G_IIf = 2·G_II", scene::ModeInteraction::Quadratic, 2.0 * shear_energy / h,
       2.0 / 3.0 * (tension_energy + shear_energy), strength * h / std::sqrt(2.0)},
  };
  for (const Case& c : cases) {
    js.mode_interaction = c.interaction;
    js.shear_fracture_energy = c.shear_fracture_energy;
    const MixedRun r = pull_and_slide_until_broken(sc, h, pull, slide, 20000);
    const MixedRun half = pull_and_slide_until_broken(sc, h, 0.5 * pull, 0.5 * slide, 40000);
    BOOST_REQUIRE(r.break_step > 0 && half.break_step > 0);
    const double excess = r.dissipated - c.expected, excess_half = half.dissipated - c.expected;
    BOOST_TEST_MESSAGE(c.name << ": peak normal force " << r.peak_normal << " N/m against the onset " << c.onset
                              << ", break at step " << r.break_step << ", dissipated " << r.dissipated
                              << " J/m against " << c.expected << " (" << excess / c.expected << "; at half the speed "
                              << excess_half / c.expected << ", bound " << lag_bound / c.expected
                              << "), mix changed by " << r.largest_mix_change << ", balance "
                              << r.largest_balance_error);
    BOOST_TEST(r.largest_mix_change <= kLargestMixChange);  // the drive is proportional
    BOOST_TEST(r.peak_normal <= c.onset * (1.0 + r.largest_mix_change));
    BOOST_TEST(r.peak_normal >= c.onset - 2.0 * js.normal_stiffness * opening_step);
    BOOST_TEST(excess >= 0.0);
    BOOST_TEST(excess <= lag_bound);
    BOOST_TEST(excess_half >= 0.0);
    BOOST_TEST(excess_half <= 0.6 * excess);
    BOOST_TEST(r.largest_balance_error <= 1e-4);
  }
}
