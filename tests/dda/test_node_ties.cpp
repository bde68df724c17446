// The copies of a mesh node tied while its fan is intact (analysis.intact_nodes = "tie") and the
// fracture criterion on the blocks' stress load (analysis.fracture_load = "block_stress"): each
// case checks a number against the spring's definition, the ledger, or a uniform stress field.
#define BOOST_TEST_MODULE dda_node_ties
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <tuple>
#include <vector>

#include "ddafrac/dda/engine.hpp"
#include "fan_scene.hpp"
#include "support.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;
using testing::deepest_vertex_inside;
using testing::Fan;

namespace {

/// In the fan, triangles k and k + 2, k + 3, k + 4 (mod 6) meet only at the centre node.
constexpr int kNodeOnlyPairs = 9;

/// The tied contacts of the engine's list.
std::vector<Contact> ties(const Engine& e) {
  std::vector<Contact> out;
  for (const Contact& c : e.contacts().contacts)
    if (c.tied) out.push_back(c);
  return out;
}

/// ½·kn·|x_v − x_u|², J/m: the energy of a tie whose copies are at the engine's current positions
/// (x_u: the copy at the end of the reference edge that holds it, Contact::ref_t 0 or 1).
double tie_energy_from_positions(const Engine& e, const Contact& c) {
  const BlockSystem& s = e.blocks();
  const Index u = c.ref_t == 0.0 ? c.edge0 : c.edge1;
  const double dx = s.vx[c.vertex] - s.vx[u], dy = s.vy[c.vertex] - s.vy[u];
  return 0.5 * c.kn * (dx * dx + dy * dy);
}

Fan tied_fan() {
  Fan fan;
  fan.scene.analysis.intact_nodes = scene::IntactNodes::Tie;
  return fan;
}

EngineOptions fan_options() {
  EngineOptions o;
  o.allowed_displacement = 2e-6;  // m, as the fan test of dda_energy
  return o;
}

}  // namespace

// While the fan is intact, each of its 9 node-only pairs holds one tie, and what a tie stores
// is ½·kn·|x_v − x_u|² of its two copies, measured on the moved geometry, whatever line the
// detection chose: isotropic, with no state. The stored energy is booked from the step's
// linearised gap and shear, so it differs from the exact distance by the linearisation's error,
// second order in the step's increment (5e-6 of the largest tie's energy here): 1e-4.
BOOST_AUTO_TEST_CASE(a_tie_stores_half_kn_times_the_squared_distance_of_its_copies) {
  Fan fan = tied_fan();
  scene::JointSet& rock = fan.scene.joint_sets.back();
  rock.tensile_strength = rock.cohesion = 1e30;  // Pa: squeezed without breaking
  Engine e(fan.scene, fan.mesh, fan_options());
  for (int k = 0; k < 400; ++k) e.step();
  BOOST_REQUIRE_EQUAL(e.crack_counts().total, 0);
  const std::vector<Contact> held = ties(e);
  BOOST_TEST(static_cast<int>(held.size()) == kNodeOnlyPairs);
  double largest = 0.0, worst = 0.0;
  for (const Contact& c : held) largest = std::max(largest, tie_energy_from_positions(e, c));
  BOOST_REQUIRE(largest > 0.0);
  for (const Contact& c : held) {
    BOOST_TEST(c.ks == c.kn);
    BOOST_TEST(static_cast<int>(c.state) == static_cast<int>(ContactState::Locked));
    worst = std::max(worst, std::abs(c.stored_normal + c.stored_shear - tie_energy_from_positions(e, c)));
  }
  BOOST_TEST_MESSAGE("fan at t = " << e.time() << " s: " << held.size() << " ties, largest " << largest
                                   << " J/m, largest |booked - ½·kn·|Δx|²| " << worst << " J/m");
  BOOST_TEST(worst <= 1e-4 * largest);
}

namespace {
/// A tie's identity across steps: its block pair and its node (a corner's contact may swap vertex
/// and edge between steps).
using TieKey = std::tuple<Index, Index, meshes::Index>;

/// What every tie of the engine's list stored at the end of the last step, J/m.
std::map<TieKey, double> tie_energies(const Engine& e) {
  std::map<TieKey, double> out;
  for (const Contact& c : e.contacts().contacts)
    if (c.tied)
      out[{c.pair_low(), c.pair_high(), e.blocks().vertex_node[static_cast<std::size_t>(c.vertex)]}] =
          c.stored_normal + c.stored_shear;
  return out;
}

/// What the contacts of the joints that the last fracture check broke stored, J/m.
double breaking_joints_energy(const Engine& e) {
  double sum = 0.0;
  for (const Contact& c : e.contacts().contacts)
    if (c.joint >= 0 && c.was_bonded && e.blocks().joints[static_cast<std::size_t>(c.joint)].broken)
      sum += c.stored_normal + c.stored_shear;
  return sum;
}
}  // namespace

// Squeezed until its joints break: a tie holds while intact joints at the node still connect its
// two blocks around the node, so a crack that only ends at the node keeps every tie, and one
// that passes through it releases the ties across it. In every step that releases ties, the
// ledger books what they stored as released by the breaks: joint_break_loss grows by at least
// their energy and by no more than that plus what the contacts of the joints just broken stored.
// Before and after, node-sharing triangles never overlap deeper than one step's allowed
// displacement and the ledger closes within 1% (as without ties, dda_energy).
BOOST_AUTO_TEST_CASE(a_crack_through_a_node_releases_its_ties_to_the_joint_breaks) {
  const Fan fan = tied_fan();
  Engine e(fan.scene, fan.mesh, fan_options());
  double deepest = 0.0;
  long steps_after_break = 0, release_steps = 0;
  std::size_t ties_after_first_crack = 0;
  std::map<TieKey, double> tied_before;
  double breaking_before = 0.0;
  while (e.time() < 1e-3 && steps_after_break < 3000) {
    const double breaks_before = e.ledger().total.joint_breaks;
    e.step();
    if (e.crack_counts().total > 0 && ++steps_after_break == 2) ties_after_first_crack = ties(e).size();
    for (Index p = 0; p < 6; ++p)
      for (Index q = 0; q < 6; ++q)
        if ((p - q + 6) % 6 >= 2 && (p - q + 6) % 6 <= 4)
          deepest = std::max(deepest, deepest_vertex_inside(e.blocks(), p, q));
    const std::map<TieKey, double> tied_now = tie_energies(e);
    double released = 0.0;
    for (const auto& [key, stored] : tied_before)
      if (tied_now.count(key) == 0) released += stored;
    if (released > 0.0) {
      ++release_steps;
      const double booked = e.ledger().total.joint_breaks - breaks_before;
      BOOST_TEST_MESSAGE("t = " << e.time() << " s: " << tied_before.size() - tied_now.size()
                                << " ties released, they stored " << released << " J/m, the joints just broken "
                                << breaking_before << ", booked to joint breaks " << booked);
      BOOST_TEST(booked >= released * (1.0 - 1e-12));
      BOOST_TEST(booked <= (released + breaking_before) * (1.0 + 1e-12));
    }
    tied_before = tied_now;
    breaking_before = breaking_joints_energy(e);
  }
  const EnergyLedger& l = e.ledger();
  BOOST_TEST_MESSAGE("tied fan: " << e.crack_counts().total << " joints broken by t = " << e.time()
                                  << " s, ties left after the first crack " << ties_after_first_crack
                                  << ", deepest overlap of node-sharing triangles " << deepest << " m (allowed "
                                  << e.allowed_displacement() << "), released by breaks " << l.total.joint_breaks
                                  << " J/m, largest balance error " << l.largest_balance_error);
  BOOST_TEST(e.crack_counts().total >= 2);
  BOOST_TEST(release_steps >= 1);
  BOOST_TEST(steps_after_break >= 1000);
  BOOST_TEST(deepest <= e.allowed_displacement());
  BOOST_TEST(l.largest_balance_error <= 0.01);
  BOOST_TEST(e.statistics().missed_contacts == 0);
  // Every tie that went was released by a break, none by the detection's choice of line.
  BOOST_TEST(e.statistics().ties_lost == 0);
}

namespace {
/// A bar L x H of nx x ny squares, each split into two triangles (one body with virtual joints of
/// strength σt), the nodes at x = 0 held and those at x = L pulled by σ·H in static mode.
struct PulledBar {
  double length = 0.1, height = 0.01;  // m
  double sigma = 1e6;                  // Pa, applied tension
  double tensile_strength = 2e6;       // Pa: twice the load, so nothing breaks
  int nx = 20, ny = 2;
  double stress_radius = 0.0;  // m, analysis.fracture_stress_radius
};

Engine pulled_bar(const PulledBar& b, scene::IntactNodes nodes, scene::FractureLoad load) {
  const meshes::Mesh m = testing::triangulated_bar(b.length, b.height, b.nx, b.ny);
  auto node = [&](int i, int j) { return static_cast<std::size_t>(j * (b.nx + 1) + i); };  // its node numbering
  const double kn = 1e11;  // N/m, 10 E
  scene::Scene sc = testing::basic_scene(scene::Mode::Static, 1.0, kn, {0.0, 0.0});
  scene::JointSet rock;
  rock.name = "rock";
  rock.friction_angle = 0.5;  // rad
  rock.cohesion = 1e30;       // Pa: no shear failure
  rock.tensile_strength = b.tensile_strength;
  rock.normal_stiffness = kn;
  rock.shear_stiffness = 0.4 * kn;
  sc.joint_sets.push_back(rock);
  scene::Body body = testing::body("rock");
  body.virtual_joints = 1;
  sc.bodies.push_back(body);
  sc.analysis.intact_nodes = nodes;
  sc.analysis.fracture_load = load;
  sc.analysis.fracture_stress_radius = b.stress_radius;
  // Held: every vertex at x = 0. Pulled: σ·H spread as a linear element's consistent nodal
  // forces over the nodes at x = L (half at the two corners), each node's share over its copies.
  EngineOptions opt;
  std::vector<std::vector<Index>> copies(m.nodes.size());  // blocks holding a copy of each node
  for (std::size_t c = 0; c + 1 < m.cell_offsets.size(); ++c)
    for (auto k = m.cell_offsets[c]; k < m.cell_offsets[c + 1]; ++k) {
      const auto n = static_cast<std::size_t>(m.cell_nodes[static_cast<std::size_t>(k)]);
      const meshes::Point& p = m.nodes[n];
      if (p.x == 0.0) opt.anchors.push_back({static_cast<Index>(c), p.x, p.y, p.x, p.y, 0.0, 0.0});
      copies[n].push_back(static_cast<Index>(c));
    }
  for (int j = 0; j <= b.ny; ++j) {
    const std::size_t n = node(b.nx, j);
    const double share = (j == 0 || j == b.ny ? 0.5 : 1.0) * b.sigma * b.height / b.ny;  // N/m
    const meshes::Point& p = m.nodes[n];
    for (const Index block : copies[n])
      opt.point_loads.push_back({block, p.x, p.y, share / static_cast<double>(copies[n].size()), 0.0});
  }
  return Engine(sc, m, opt);
}

/// The criterion's r1 of the joints across the bar (normal along x) in its middle half, away
/// from the held and the pulled end (and the stress radius inside it: what the criterion
/// averages lies in the middle half too).
std::vector<double> cross_joint_ratios(const Engine& e, const PulledBar& b) {
  const double from = 0.25 * b.length + b.stress_radius, to = 0.75 * b.length - b.stress_radius;
  const std::vector<FailureRatios> ratio = e.joint_ratios(e.fracture_loads(e.joint_forces()));
  std::vector<double> out;
  for (std::size_t j = 0; j < e.blocks().joints.size(); ++j) {
    const Joint& jt = e.blocks().joints[j];
    const meshes::Point t = e.blocks().joint_tangent(jt);
    const meshes::Point mid = e.blocks().joint_midpoint(jt);
    if (std::abs(t.x) < 1e-3 && mid.x > from && mid.x < to) out.push_back(ratio[j].r1);
  }
  return out;
}
}  // namespace

// A bar in uniform tension σ: the load its blocks' stress puts on each joint across the bar is
// σ·l, so the block-stress criterion's r1 is σ/σt there, whatever the ties carry past the joints
// (the blocks' stress is uniform to the solver's tolerance, 1e-3 covers the ends' influence
// decayed to the bar's middle half), and so, to the blocks' checkerboard, when the criterion
// averages the stress over a radius. The joints' own springs carry less when the copies of their
// nodes are tied, and the spring criterion then judges less than the stress says.
BOOST_AUTO_TEST_CASE(the_block_stress_criterion_judges_a_joint_on_its_blocks_stress) {
  const PulledBar b;
  const double expected = b.sigma / b.tensile_strength;
  Engine by_stress = pulled_bar(b, scene::IntactNodes::Tie, scene::FractureLoad::BlockStress);
  Engine by_springs = pulled_bar(b, scene::IntactNodes::Tie, scene::FractureLoad::JointSprings);
  PulledBar averaging = b;
  averaging.stress_radius = 0.5 * b.height;  // the bar's blocks within it, not those near its ends
  Engine by_mean_stress = pulled_bar(averaging, scene::IntactNodes::Tie, scene::FractureLoad::BlockStress);
  for (int k = 0; k < 4; ++k) {
    by_stress.step();
    by_springs.step();
    by_mean_stress.step();
  }
  const std::vector<double> stress = cross_joint_ratios(by_stress, b), springs = cross_joint_ratios(by_springs, b);
  const std::vector<double> mean_stress = cross_joint_ratios(by_mean_stress, averaging);
  BOOST_REQUIRE(!stress.empty());
  BOOST_REQUIRE(!mean_stress.empty());
  BOOST_REQUIRE_EQUAL(stress.size(), springs.size());
  double worst = 0.0, worst_mean = 0.0, springs_largest = 0.0;
  for (std::size_t k = 0; k < stress.size(); ++k) {
    worst = std::max(worst, std::abs(stress[k] - expected));
    springs_largest = std::max(springs_largest, springs[k]);
  }
  for (const double r1 : mean_stress) worst_mean = std::max(worst_mean, std::abs(r1 - expected));
  double sxx_low = 1e300, sxx_high = -1e300;  // Pa, of the blocks in the bar's middle half
  for (std::size_t k = 0; k < by_mean_stress.blocks().block_count(); ++k) {
    const double x = by_mean_stress.blocks().geometry[k].cx;
    if (x < 0.25 * b.length || x > 0.75 * b.length) continue;
    sxx_low = std::min(sxx_low, by_mean_stress.blocks().stress[k][0]);
    sxx_high = std::max(sxx_high, by_mean_stress.blocks().stress[k][0]);
  }
  BOOST_TEST_MESSAGE("blocks' σxx in the middle half: " << sxx_low / b.sigma << " to " << sxx_high / b.sigma
                                                        << " of σ");
  BOOST_TEST_MESSAGE("pulled bar with ties: " << stress.size() << " joints across its middle, r1 by the blocks' stress "
                                              << "within " << worst << " of σ/σt = " << expected << ", by their mean "
                                              << "over " << averaging.stress_radius << " m within " << worst_mean
                                              << "; by the joints' springs at most " << springs_largest);
  BOOST_TEST(worst <= 1e-3 * expected);
  // The two triangles of each square carry σxx a percent apart, in a checkerboard that a joint's
  // own two blocks (one of each kind) cancel; the dozen blocks within the radius cancel it but
  // for the few of one kind in excess: their mean keeps within a quarter of the swing.
  BOOST_TEST(worst_mean <= 0.25 * (sxx_high - sxx_low) / b.tensile_strength);
  BOOST_TEST(springs_largest < 0.99 * expected);
  BOOST_TEST(ties(by_stress).size() > 0u);
}
