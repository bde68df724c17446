// Unit tests of the DDA building blocks: closed-form polygon integrals, the contact
// linearisation against finite differences, detection on a glued mesh, PCG against the direct solver.
#define BOOST_TEST_MODULE dda_unit
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <vector>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/dda/contact_mechanics.hpp"
#include "ddafrac/dda/drive.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/dda/geometry.hpp"
#include "ddafrac/dda/linear_system.hpp"
#include "ddafrac/dda/softening.hpp"
#include "ddafrac/dda/synthetic.hpp"
#include "support.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;

namespace {
/// Closed forms are exact up to round-off: 1e-12 relative.
constexpr double kExact = 1e-12;
bool close(double a, double b, double tol) { return std::abs(a - b) <= tol * std::max(1.0, std::abs(b)); }
/// How far vertex v lies behind the line of the CCW edge e0 -> e1, m (positive: on the block's side).
double depth_behind_edge(const BlockSystem& b, Index v, Index e0, Index e1) {
  const double ex = b.vx[e1] - b.vx[e0], ey = b.vy[e1] - b.vy[e0];
  return (ex * (b.vy[v] - b.vy[e0]) - ey * (b.vx[v] - b.vx[e0])) / std::hypot(ex, ey);
}
}  // namespace

BOOST_AUTO_TEST_CASE(rectangle_far_from_origin) {
  const double w = 2.0, h = 0.5, x0 = 1e3, y0 = -2e3;
  const double x[] = {x0, x0 + w, x0 + w, x0};
  const double y[] = {y0, y0, y0 + h, y0 + h};
  const PolygonIntegrals g = polygon_integrals(x, y, 4);
  BOOST_TEST(close(g.area, w * h, kExact));
  BOOST_TEST(close(g.cx, x0 + w / 2, kExact));
  BOOST_TEST(close(g.cy, y0 + h / 2, kExact));
  BOOST_TEST(close(g.sxx / (w * w * w * h / 12), 1.0, 1e-9));
  BOOST_TEST(close(g.syy / (w * h * h * h / 12), 1.0, 1e-9));
  BOOST_TEST(std::abs(g.sxy) <= 1e-9 * g.sxx);
}

BOOST_AUTO_TEST_CASE(right_triangle_product_moment) {
  // Right triangle legs a (x) and b (y): Sxy about the centroid = -a²b²/72 for this orientation.
  const double a = 3.0, b = 2.0;
  const double x[] = {0.0, a, 0.0};
  const double y[] = {0.0, 0.0, b};
  const PolygonIntegrals g = polygon_integrals(x, y, 3);
  BOOST_TEST(close(g.area, a * b / 2, kExact));
  BOOST_TEST(close(g.sxx, a * a * a * b / 36, kExact));
  BOOST_TEST(close(g.syy, a * b * b * b / 36, kExact));
  BOOST_TEST(close(g.sxy, -a * a * b * b / 72, kExact));
}

BOOST_AUTO_TEST_CASE(concave_l_shape_equals_two_rectangles) {
  // L = [0,2]x[0,1] ∪ [0,1]x[1,2]; parallel-axis theorem on the two rectangles.
  const double x[] = {0, 2, 2, 1, 1, 0};
  const double y[] = {0, 0, 1, 1, 2, 2};
  const PolygonIntegrals g = polygon_integrals(x, y, 6);
  const double a1 = 2, c1x = 1, c1y = 0.5, a2 = 1, c2x = 0.5, c2y = 1.5;
  const double area = a1 + a2, cx = (a1 * c1x + a2 * c2x) / area, cy = (a1 * c1y + a2 * c2y) / area;
  const double sxx = 8.0 / 12 + a1 * (c1x - cx) * (c1x - cx) + 1.0 / 12 + a2 * (c2x - cx) * (c2x - cx);
  const double syy = 2.0 / 12 + a1 * (c1y - cy) * (c1y - cy) + 1.0 / 12 + a2 * (c2y - cy) * (c2y - cy);
  const double sxy = a1 * (c1x - cx) * (c1y - cy) + a2 * (c2x - cx) * (c2y - cy);
  BOOST_TEST(close(g.area, area, kExact));
  BOOST_TEST(close(g.cx, cx, kExact));
  BOOST_TEST(close(g.cy, cy, kExact));
  BOOST_TEST(close(g.sxx, sxx, kExact));
  BOOST_TEST(close(g.syy, syy, kExact));
  BOOST_TEST(close(g.sxy, sxy, kExact));
}

BOOST_AUTO_TEST_CASE(mass_integral_matches_quadrature) {
  // ∫TᵀT over a triangle with the 3-point edge-midpoint rule (exact for quadratics).
  const double x[] = {0.1, 1.3, 0.4};
  const double y[] = {-0.2, 0.3, 1.1};
  const PolygonIntegrals g = polygon_integrals(x, y, 3);
  Mat6 q = Mat6::Zero();
  for (int k = 0; k < 3; ++k) {
    const double mx = 0.5 * (x[k] + x[(k + 1) % 3]), my = 0.5 * (y[k] + y[(k + 1) % 3]);
    const Mat26 t = displacement_matrix(g.cx, g.cy, mx, my);
    q += (g.area / 3.0) * t.transpose() * t;
  }
  BOOST_TEST((mass_integral(g) - q).norm() <= kExact * q.norm());
}

// d ≈ d0 + e·Di + g·Dj: the exact gap of displaced points differs from the linear model by
// O(|D|²); with |D| = 1e-6 the residual is ~1e-12 while e·D is ~1e-6.
BOOST_AUTO_TEST_CASE(contact_gradients_match_finite_differences) {
  meshes::Mesh m;
  testing::add_polygon(m, "a", {{0.2, 1.05}, {0.0, 1.6}, {-0.3, 1.2}});  // vertex 0 near b's top edge
  testing::add_rectangle(m, "b", -1.0, 0.0, 1.0, 1.0);
  auto s = testing::basic_scene(scene::Mode::Dynamic, 1e-3, 1e9, {0, 0});
  s.bodies = {testing::body("a"), testing::body("b")};
  const BlockSystem bs = build_block_system(s, m, false);
  Contact c;
  c.vblock = 0;
  c.eblock = 1;
  c.vertex = 0;
  c.edge0 = 5;  // b: (1,1) -> (-1,1), the top edge, CCW
  c.edge1 = 6;
  c.state = ContactState::Locked;
  c.ref_t = 0.3;
  ContactLinearisation lin;
  linearise_contact(c, lin, bs);
  BOOST_TEST(close(c.d0, 0.05, kExact));
  const double step = 1e-6;
  for (int r = 0; r < 12; ++r) {
    Vec6 di = Vec6::Zero(), dj = Vec6::Zero();
    (r < 6 ? di[r] : dj[r - 6]) = step;
    auto moved = [&](Index v, Index b, const Vec6& d) {
      const auto& g = bs.geometry[static_cast<std::size_t>(b)];
      Eigen::Vector2d p(bs.vx[static_cast<std::size_t>(v)], bs.vy[static_cast<std::size_t>(v)]);
      return Eigen::Vector2d(p + displacement_matrix(g.cx, g.cy, p.x(), p.y()) * d);
    };
    const auto p1 = moved(0, 0, di), p2 = moved(5, 1, dj), p3 = moved(6, 1, dj);
    const double d = normal_gap(p1.x(), p1.y(), p2.x(), p2.y(), p3.x(), p3.y());
    const double linear = c.d0 + lin.e.dot(di) + lin.g.dot(dj);
    BOOST_TEST(std::abs(d - linear) <= 1e-10, "dof " << r << ": exact " << d << " linear " << linear);
    // Shear along the (undeformed) edge direction from the reference point.
    const Eigen::Vector2d u = (Eigen::Vector2d(bs.vx[6], bs.vy[6]) - Eigen::Vector2d(bs.vx[5], bs.vy[5])).normalized();
    const double sh = (p1 - (p2 + c.ref_t * (p3 - p2))).dot(u);
    BOOST_TEST(std::abs(sh - (c.s0 + lin.es.dot(di) + lin.gs.dot(dj))) <= 1e-10, "shear dof " << r);
  }
}

// A glued ring disc: every interior edge gives exactly two bonded contacts; the only other
// contacts are one per pair of triangles that meet at a mesh node alone, open at zero gap.
BOOST_AUTO_TEST_CASE(glued_disc_contacts_are_two_per_joint_and_one_per_shared_node) {
  const meshes::Mesh m = make_ring_disc_mesh(0.1, 600, 0.1, 0.0);
  auto s = make_impact_scene(0.0, 1e-6);
  s.bodies.pop_back();
  Engine e(s, m);
  e.step();
  const auto& cs = e.contacts().contacts;
  std::size_t bonded = 0, node_contacts = 0;
  std::set<std::pair<Index, Index>> node_pairs;
  for (const Contact& c : cs) {
    if (c.bonded(e.blocks().joints)) {
      ++bonded;
      continue;
    }
    BOOST_TEST(c.shared_node);
    BOOST_TEST((c.state == ContactState::Open));
    BOOST_TEST(std::abs(c.d0) <= 1e-15);
    ++node_contacts;
    node_pairs.insert({c.pair_low(), c.pair_high()});
  }
  BOOST_TEST(e.blocks().joints.size() > 0u);
  BOOST_TEST(bonded == 2 * e.blocks().joints.size());
  BOOST_TEST(node_contacts > e.blocks().joints.size() / 2);
  BOOST_TEST(node_pairs.size() == node_contacts);
}

// A corner that enters a block through one face is held on that face. The wedge of the
// striker's corner dips 5° behind the wall's top face (beyond the 3° the angle rule allows), so
// the vertex-edge rule pairs it only with the wall's right face, 100 µm away behind it; the
// corner lies 0.1 µm behind the top face, its entrance line, and its contact must be there
// (paired with the right face, its spring would hold ½·kn·(100 µm)² that no work put in).
BOOST_AUTO_TEST_CASE(a_corner_entering_through_one_face_is_held_on_that_face) {
  constexpr double kSide = 10e-3, kInset = 0.1e-3, kDepth = 0.1e-6, kArm = 3e-3;  // m
  constexpr double kDip = 5.0 * common::kRadiansPerDegree, kRise = 60.0 * common::kRadiansPerDegree;  // rad
  const meshes::Point corner{kSide - kInset, -kDepth};
  meshes::Mesh m;
  testing::add_polygon(m, "striker",
                       {corner,
                        {corner.x + kArm * std::cos(kDip), corner.y - kArm * std::sin(kDip)},
                        {corner.x + kArm * std::cos(kRise), corner.y + kArm * std::sin(kRise)}});
  testing::add_rectangle(m, "wall", 0.0, -kSide, kSide, 0.0);
  auto s = testing::basic_scene(scene::Mode::Dynamic, 1e-7, 1e10, {0, 0});
  s.bodies = {testing::body("striker"), testing::body("wall", scene::Motion::Fixed)};
  EngineOptions o;
  o.allowed_displacement = 2e-6;  // m: a search distance of 5 µm, well short of the 100 µm
  Engine e(s, m, o);
  e.step();
  const BlockSystem& b = e.blocks();
  const Contact* held = nullptr;
  for (const Contact& c : e.contacts().contacts)  // the striker's first vertex is the corner
    if (c.vertex == b.begin(0)) held = &c;
  BOOST_TEST_REQUIRE(held != nullptr);
  BOOST_TEST_MESSAGE("corner held at gap " << held->d0 << " m on the edge from (" << b.vx[held->edge0] << ", "
                                           << b.vy[held->edge0] << ")");
  BOOST_TEST(std::abs(b.vy[held->edge0]) < kDepth);  // the top face
  BOOST_TEST(std::abs(b.vy[held->edge1]) < kDepth);
  BOOST_TEST(held->d0 == -kDepth, boost::test_tools::tolerance(1e-6));
}

namespace {
/// Two triangles of one body that meet only at a mesh node (node 0 at the origin): a to the upper
/// left of the node, its edge into the node coming from (a_far_x, a_far_y); b to the lower right,
/// its edge into the node level (along -x). Both CCW.
meshes::Mesh node_fan_pair(double a_far_x, double a_far_y) {
  constexpr double kMm = 1e-3;  // m per mm
  meshes::Mesh m;
  m.body_names = {"rock"};
  m.nodes = {{0.0, 0.0}, {a_far_x, a_far_y}, {-0.5 * kMm, 2.5 * kMm}, {-1.0 * kMm, -2.5 * kMm}, {3.0 * kMm, 0.0}};
  m.cell_nodes = {1, 0, 2, 0, 3, 4};
  m.cell_offsets = {0, 3, 6};
  m.cell_body = {0, 0};
  return m;
}

/// An engine on two triangles of one body that meet only at a mesh node, node 0 the second
/// vertex of the first cell (a's copy of it: a_copy): no gravity, kn = 1e10 Pa, dt 1e-7 s, and a
/// search distance of 5 µm (a capture radius well short of the copies' 0.1–0.4 mm drift below).
struct NodeFan {
  explicit NodeFan(const meshes::Mesh& m) : engine(scene(), m, options()), blocks(engine.blocks()) {}
  static scene::Scene scene() {
    auto s = testing::basic_scene(scene::Mode::Dynamic, 1e-7, 1e10, {0, 0});
    s.bodies = {testing::body("rock")};
    return s;
  }
  static EngineOptions options() {
    EngineOptions o;
    o.allowed_displacement = 2e-6;  // m
    return o;
  }
  Engine engine;
  BlockSystem& blocks;
  const Index a_copy = blocks.begin(0) + 1;
};
}  // namespace

// Two triangles of one body that meet only at a mesh node, after the pieces around the node
// moved apart (about the geometry of a flattened disc's fragments at 1400 µs, mm about the
// node): a's copy of the node lies 0.4 mm from b's, inside b, 7 µm behind b's edge into the
// node, while b's copy lies outside a. The angle rules allow b's copy against a's edge into the
// node (its wedge 2.9° behind that edge, within the 3° tolerance), open at +3.2 µm, so the
// corner measured from there stayed open while a's copy sank into b unseen, until the rules
// switched line at 17.8 µm deep (+2% of the energy balance in one step). The copy inside must
// hold the contact, on the edge it lies least deep behind.
BOOST_AUTO_TEST_CASE(a_node_copy_inside_the_other_block_holds_the_node_contact) {
  constexpr double kMm = 1e-3;  // m per mm
  meshes::Mesh m;
  m.body_names = {"rock"};
  m.nodes = {{0.0, 0.0}, {-1.856 * kMm, 2.384 * kMm}, {1.196 * kMm, 2.073 * kMm}, {-1.014 * kMm, -2.717 * kMm},
             {1.928 * kMm, -2.342 * kMm}};
  m.cell_nodes = {1, 0, 2, 3, 4, 0};  // a above the node, b below it; both CCW
  m.cell_offsets = {0, 3, 6};
  m.cell_body = {0, 0};
  NodeFan fan(m);
  Engine& e = fan.engine;
  BlockSystem& b = fan.blocks;
  const Index copy_in_a = fan.a_copy;
  b.vx[copy_in_a] = 0.2477 * kMm;
  b.vy[copy_in_a] = -0.3123 * kMm;
  // Its depth behind b's edge from (1.928, -2.342) mm into the node (b's nearest edge).
  const Index edge0 = b.begin(1) + 1, edge1 = b.begin(1) + 2;
  const double depth = depth_behind_edge(b, copy_in_a, edge0, edge1);
  BOOST_TEST_REQUIRE(depth > 2.0 * e.allowed_displacement());  // not reached in one step
  e.step();
  const auto& contacts = e.contacts().contacts;
  BOOST_TEST_REQUIRE(contacts.size() == 1u);  // the node's one corner contact
  const Contact& c = contacts.front();
  BOOST_TEST_MESSAGE("node contact: vertex " << c.vertex << ", edge from " << c.edge0 << ", gap " << c.d0 << " m");
  BOOST_TEST(c.shared_node);
  BOOST_TEST(c.vertex == copy_in_a);
  BOOST_TEST(c.edge0 == edge0);
  BOOST_TEST(c.d0 == -depth, boost::test_tools::tolerance(1e-9));
}

// The copies of a mesh node drift apart along the edges into the node (case 4 at kn = 10·E near
// 71 µs: 107 µm along b's level edge, a's edge 1.9° down from it), and the edges overlap as a
// sliver: a's copy lies 0.1 µm inside b at the thin end, b's copy 3.5 µm inside a at the thick
// end. The node's one contact holds the deeper copy, b's, on a's edge into the node, and the
// depth it holds moves no more than the copies do at any point of the way: a's copy slides out
// from 1 µm off the node along the sliver 1 µm at a time, then rises out of b 0.02 µm at a time. (Held at
// the thin end, as the corner's largest-gap line measures it, the contact passed to b's copy when
// a's left b and the spring took ½·kn·(3.5 µm)² at once: +0.66 J/m in case 4.)
BOOST_AUTO_TEST_CASE(a_node_corner_holds_the_deeper_copy_of_a_sliver) {
  constexpr double kMm = 1e-3;                              // m per mm
  constexpr double kDrift = 0.107 * kMm, kInside = 0.1e-6;  // m: a's copy along and behind b's edge
  constexpr double kSlide = 1e-6, kRise = 0.02e-6;          // m: a's copy's moves between steps
  NodeFan fan(node_fan_pair(-3.0 * kMm, -0.1 * kMm));       // a's edge 1.9° down into the node
  Engine& e = fan.engine;
  BlockSystem& b = fan.blocks;
  const Index copy_in_a = fan.a_copy, copy_in_b = b.begin(1), a_far = b.begin(0);
  const std::vector<double> x0 = b.vx, y0 = b.vy;
  double thick_end = 0.0;  // m: b's copy's depth behind a's edge into the node, as detection finds it
  // The depth the node's contact holds with a's copy at (x, y), every other vertex where it began.
  auto held_depth = [&](double x, double y) {
    b.vx = x0;
    b.vy = y0;
    b.vx[copy_in_a] = x;
    b.vy[copy_in_a] = y;
    thick_end = depth_behind_edge(b, copy_in_b, a_far, copy_in_a);
    e.step();
    BOOST_TEST_REQUIRE(e.contacts().contacts.size() == 1u);
    return std::max(0.0, -e.contacts().contacts.front().d0);
  };
  // From 1 µm out the corner's line is b's level edge (nearer the node, b's other edge is, and a
  // closed corner keeps its line).
  double before = held_depth(kSlide, -kInside), largest_jump = 0.0;
  for (double x = 2.0 * kSlide; x <= kDrift + 0.5 * kSlide; x += kSlide) {
    const double now = held_depth(x, -kInside);
    largest_jump = std::max(largest_jump, std::abs(now - before) / kSlide);
    before = now;
  }
  for (double y = -kInside + kRise; y <= kInside + 0.5 * kRise; y += kRise) {
    const double now = held_depth(kDrift, y);
    largest_jump = std::max(largest_jump, std::abs(now - before) / kRise);
    before = now;
  }
  const Contact& c = e.contacts().contacts.front();
  BOOST_TEST_MESSAGE("held at vertex " << c.vertex << ", gap " << c.d0 << " m; largest change of the held depth "
                                       << largest_jump << " of the copy's move");
  BOOST_TEST(thick_end > 3e-6);  // m: the sliver's thick end
  BOOST_TEST(c.vertex == copy_in_b);
  BOOST_TEST(c.d0 == -thick_end, boost::test_tools::tolerance(1e-9));
  // A distance to a line moves no more than the point does.
  BOOST_TEST(largest_jump <= 1.0);
}

// A node corner can still pass at once to a copy lying deep inside the other block when the
// copies move so far in one step that it was not inside the step before (here a's far vertex is
// set 0.2 mm lower between two steps, which turns a's edge into the node 3.7° and puts b's copy
// 3.5 µm inside a, while a's copy leaves b). That contact came in deep
// (Statistics::missed_contacts) although it was carried over from the corner: its spring took
// far more than kDeepContactEnergyFraction of the balance's scale beyond what the corner's record
// held.
BOOST_AUTO_TEST_CASE(a_node_corner_passing_to_a_copy_that_sank_in_one_step_counts_as_come_in_deep) {
  constexpr double kMm = 1e-3;                              // m per mm
  constexpr double kDrift = 0.107 * kMm, kInside = 0.1e-6;  // m: a's copy along and behind b's edge
  NodeFan fan(node_fan_pair(-3.0 * kMm, 0.1 * kMm));        // a's edge into the node 1.9° up: b's copy outside a
  Engine& e = fan.engine;
  BlockSystem& b = fan.blocks;
  const Index copy_in_a = fan.a_copy, copy_in_b = b.begin(1), a_far = b.begin(0);
  b.vx[copy_in_a] = kDrift;
  b.vy[copy_in_a] = -kInside;
  e.step();
  BOOST_TEST_REQUIRE(e.contacts().contacts.size() == 1u);
  BOOST_TEST_REQUIRE(e.contacts().contacts.front().vertex == copy_in_a);  // the corner holds a's copy
  b.vy[a_far] -= 0.2 * kMm;
  b.vy[copy_in_a] = b.vy[copy_in_b] + kInside;  // a's copy leaves b (b's edge into the node is level)
  // b's copy's depth behind a's edge from its far vertex into a's copy, as the next step finds it.
  const double depth = depth_behind_edge(b, copy_in_b, a_far, copy_in_a);
  e.step();
  BOOST_TEST_REQUIRE(e.contacts().contacts.size() == 1u);
  const Contact& c = e.contacts().contacts.front();
  BOOST_TEST_REQUIRE(c.vertex == copy_in_b);
  BOOST_TEST(c.carried);  // so the depth rule alone (first found deep) would not count it
  BOOST_TEST(c.d0 == -depth, boost::test_tools::tolerance(1e-9));
  BOOST_TEST_MESSAGE("the contact passed to b's copy at gap " << c.d0 << " m, taking " << 0.5 * c.kn * c.d0 * c.d0
                                                              << " J/m; balance scale " << e.ledger().scale()
                                                              << " J/m");
  BOOST_TEST(depth > 1e-6);
  BOOST_TEST(e.statistics().missed_contacts == 1);
  BOOST_TEST(e.statistics().deepest_missed == depth, boost::test_tools::tolerance(1e-6));
}

/// A disc hitting the ground at 20 m/s with virtual joints at 5% of their strength: it cracks
/// within the first 200 steps.
scene::Scene cracking_impact_scene() {
  scene::Scene s = make_impact_scene(20.0, 1e-3);
  constexpr double kWeakening = 0.05;  // of the virtual joints' strengths
  for (auto& js : s.joint_sets) {
    js.tensile_strength *= kWeakening;
    js.cohesion *= kWeakening;
  }
  return s;
}

// The contact pair list (Verlet list) is an optimisation only: with the default skin, with no
// skin (rebuilt whenever a vertex moved) and with a 4x wider skin, a disc hitting a plate at
// 20 m/s with weak joints (it cracks) finds the same contacts in the same states and the same
// displacements, bit for bit, at every step; the wider the skin, the fewer the rebuilds. Most
// pairs are judged quiet (PairHint: only their topological contacts), so the equality also checks
// that skipping the geometric rules for them loses nothing, over the longer life of a wide skin's
// hints too.
BOOST_AUTO_TEST_CASE(the_pair_list_changes_no_contact) {
  const meshes::Mesh m = make_ring_disc_mesh(0.1, 600);
  const scene::Scene s = cracking_impact_scene();
  auto with_skin = [&s](double factor) {
    scene::Scene t = s;
    t.analysis.pair_list_skin_factor = factor;
    return t;
  };
  Engine reference(with_skin(1.0), m), none(with_skin(0.0), m), wide(with_skin(4.0), m);
  constexpr int kSteps = 200;
  int mismatches = 0;
  for (int k = 0; k < kSteps; ++k) {
    reference.step();
    for (Engine* e : {&none, &wide}) {
      e->step();
      const auto& a = reference.contacts().contacts;
      const auto& b = e->contacts().contacts;
      bool same = a.size() == b.size() && reference.last_displacement() == e->last_displacement();
      for (std::size_t c = 0; same && c < a.size(); ++c)
        same = a[c].vblock == b[c].vblock && a[c].eblock == b[c].eblock && a[c].vertex == b[c].vertex &&
               a[c].edge0 == b[c].edge0 && a[c].state == b[c].state;
      if (!same) ++mismatches;
    }
  }
  BOOST_TEST_MESSAGE("pair-list builds over "
                     << kSteps << " steps: default skin " << reference.statistics().pair_list_builds << ", none "
                     << none.statistics().pair_list_builds << ", 4x skin " << wide.statistics().pair_list_builds
                     << "; cracks " << reference.crack_counts().total << "; quiet pairs judged "
                     << reference.detection().quiet_pairs_judged << " of " << reference.detection().pairs_judged
                     << " (4x skin " << wide.detection().quiet_pairs_judged << ")");
  BOOST_TEST(mismatches == 0);
  BOOST_TEST(reference.crack_counts().total > 0);
  BOOST_TEST(none.statistics().pair_list_builds >= kSteps - 1);
  BOOST_TEST(reference.statistics().pair_list_builds < kSteps / 2);  // 54 of 200 at 20 m/s
  BOOST_TEST(wide.statistics().pair_list_builds <= reference.statistics().pair_list_builds);
  for (const Engine* e : {&reference, &wide})
    BOOST_TEST(e->detection().quiet_pairs_judged > e->detection().pairs_judged / 2);
}

// An engine given another's carried state (a checkpoint) continues exactly as that one does:
// same contacts, displacements, stresses, cracks and energies, bit for bit, through cracking.
BOOST_AUTO_TEST_CASE(a_restored_state_continues_bit_for_bit) {
  const meshes::Mesh m = make_ring_disc_mesh(0.1, 600);
  const scene::Scene s = cracking_impact_scene();
  constexpr int kStepsBefore = 60, kStepsAfter = 140;
  Engine original(s, m);
  for (int k = 0; k < kStepsBefore; ++k) original.step();
  Engine resumed(s, m);
  resumed.restore_carried_state(original.carried_state());
  for (int k = 0; k < kStepsAfter; ++k) {
    original.step();
    resumed.step();
  }
  const BlockSystem& a = original.blocks();
  const BlockSystem& b = resumed.blocks();
  BOOST_TEST_MESSAGE("after " << kStepsBefore + kStepsAfter << " steps: " << original.crack_counts().total
                              << " cracks, " << original.contacts().contacts.size() << " contacts");
  BOOST_TEST(original.crack_counts().total > 0);
  BOOST_TEST(original.time() == resumed.time());
  BOOST_TEST(original.dt() == resumed.dt());
  BOOST_TEST((a.vx == b.vx && a.vy == b.vy));
  BOOST_TEST((a.stress == b.stress && a.velocity == b.velocity));
  BOOST_TEST(original.last_displacement() == resumed.last_displacement());
  BOOST_TEST(original.cracks().size() == resumed.cracks().size());
  BOOST_TEST(original.ledger().balance_error() == resumed.ledger().balance_error());
  BOOST_TEST(original.statistics().cg_total == resumed.statistics().cg_total);
  // Engines built from one scene and mesh start from the same bytes: what a checkpoint's
  // fingerprint of the state at t = 0 relies on.
  BOOST_TEST(Engine(s, m).carried_state() == Engine(s, m).carried_state());
}

// The time loop lands on every landing time and on the end time: 2.5 and 5 steps of dt_max and
// an end at 6.5 take 3 + 3 + 2 steps, the last ones shortened; a hook's Stop ends it early, and
// an interrupt wins even at the end time.
BOOST_AUTO_TEST_CASE(the_driver_lands_on_every_landing_time_and_on_the_end_time) {
  const meshes::Mesh m = make_ring_disc_mesh(0.1, 200);
  const scene::Scene s = make_impact_scene(3.5, 1e-3);
  const double dt = s.analysis.dt_max;
  Engine engine(s, m);
  std::vector<double> times;
  DriveHooks hooks;
  hooks.land_at = [&] {
    for (const double t : {2.5 * dt, 5.0 * dt})
      if (!reached(engine.time(), t)) return t;
    return 6.5 * dt;
  };
  hooks.after_step = [&](const StepReport& r) {
    times.push_back(r.time);
    return Next::Continue;
  };
  BOOST_TEST((drive(engine, 6.5 * dt, hooks) == DriveEnd::Reached));
  BOOST_REQUIRE(times.size() == 8u);
  BOOST_TEST(times[2] == 2.5 * dt, boost::test_tools::tolerance(kTimeSlack));
  BOOST_TEST(times[5] == 5.0 * dt, boost::test_tools::tolerance(kTimeSlack));
  BOOST_TEST(times[7] == 6.5 * dt, boost::test_tools::tolerance(kTimeSlack));
  BOOST_TEST((drive(engine, 6.5 * dt, {}) == DriveEnd::Reached));  // already there: no step
  BOOST_TEST(engine.statistics().steps == 8);

  Engine stopped(s, m);
  hooks = {};
  hooks.after_step = [&](const StepReport& r) { return r.step == 3 ? Next::Stop : Next::Continue; };
  BOOST_TEST((drive(stopped, 6.5 * dt, hooks) == DriveEnd::Stopped));
  BOOST_TEST(stopped.statistics().steps == 3);
  hooks = {};
  hooks.interrupt = [] { return Next::Stop; };
  BOOST_TEST((drive(engine, 6.5 * dt, hooks) == DriveEnd::Stopped));
}

// Bodies that interpenetrate at t = 0 are reported: the plate raised into the disc by twice the
// allowed step displacement gives overlapping contacts at the first step, the deepest exactly that
// deep; the plate where it belongs gives none.
BOOST_AUTO_TEST_CASE(an_overlap_at_the_start_is_counted) {
  const scene::Scene s = make_impact_scene(3.5, 1e-3);
  meshes::Mesh touching = make_ring_disc_mesh(0.1, 600);
  Engine reference(s, touching);
  const double overlap = 2.0 * reference.allowed_displacement();
  meshes::Mesh raised = touching;
  constexpr std::size_t kPlateCorners = 4;  // the plate is the mesh's last cell, a rectangle
  for (std::size_t k = raised.nodes.size() - kPlateCorners; k < raised.nodes.size(); ++k) raised.nodes[k].y += overlap;
  Engine overlapping(s, raised);
  reference.step();
  overlapping.step();
  BOOST_TEST(reference.statistics().initial_overlaps == 0);
  BOOST_TEST(overlapping.statistics().initial_overlaps > 0);
  BOOST_TEST(overlapping.statistics().deepest_initial_overlap == overlap, boost::test_tools::tolerance(1e-9));
}

// PCG with block-Jacobi agrees with the sparse LDLT to the PCG tolerance (1e-12 relative residual
// on a well-conditioned dynamic system gives ~1e-10 relative solution error).
BOOST_AUTO_TEST_CASE(pcg_matches_direct_solver) {
  const meshes::Mesh m = make_ring_disc_mesh(0.1, 600);
  scene::Scene s = make_impact_scene(3.5, 1e-3);
  s.analysis.solver_tolerance = 1e-12;
  EngineOptions direct;
  direct.solver.kind = SolverKind::Direct;
  Engine a(s, m);
  Engine b(s, m, direct);
  BOOST_TEST(a.options().solver.tolerance == s.analysis.solver_tolerance);  // the scene's key reaches PCG
  a.step();
  b.step();
  double diff = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < a.last_displacement().size(); ++i) {
    diff = std::max(diff, (a.last_displacement()[i] - b.last_displacement()[i]).cwiseAbs().maxCoeff());
    norm = std::max(norm, b.last_displacement()[i].cwiseAbs().maxCoeff());
  }
  BOOST_TEST_MESSAGE("PCG vs LDLT: max |ΔD| " << diff << " of max |D| " << norm << ", CG iterations per solve "
                                              << static_cast<double>(a.statistics().cg_total) / a.statistics().solves);
  BOOST_TEST(diff <= 1e-8 * norm);
}

// Regression (default impact scene, t ≈ 18.8 µs): a locked contact whose carried shear exceeds a
// friction limit that fell with fn, while the contact unloads slightly. The old rule judged a
// sliding contact by the direction of its step increment, so it flipped locked -> sliding ->
// locked until dt underflowed. With the elastic predictor, sliding is a fixed point.
BOOST_AUTO_TEST_CASE(sliding_is_a_fixed_point_when_the_carried_shear_exceeds_a_falling_limit) {
  Contact c;
  c.kn = 3.5e8;
  c.ks = 1.4e8;
  c.tan_phi = 0.364;
  c.state = c.trial = ContactState::Locked;
  c.d0 = -7.08e-7;
  c.s0 = -5.11e-7;
  ContactLinearisation lin;  // zero
  lin.e[kU] = 1.0;   // d = d0 + D_v[u]
  lin.es[kV] = 1.0;  // s = s0 + D_v[v]
  Vec6 dv = Vec6::Zero();
  dv[kU] = -5.26e-7 - c.d0;  // fn = 184 N/m, limit tanφ·fn = 67 N/m
  dv[kV] = 1.2e-8;           // unloading: s = -4.99e-7 m, spring 69.9 N/m > limit
  const Vec6 de = Vec6::Zero();
  const double tol = 6e-10;
  BOOST_TEST(judge_contact(c, lin, dv, de, false, tol));
  BOOST_TEST(static_cast<int>(c.trial) == static_cast<int>(ContactState::Sliding));
  BOOST_TEST(c.slide_sign == -1.0);
  // The sliding solution moves on the same way: no further change.
  BOOST_TEST(!judge_contact(c, lin, dv, de, false, tol));
  BOOST_TEST(static_cast<int>(c.trial) == static_cast<int>(ContactState::Sliding));
  // Commit: the elastic part stays at the limit, the reference point takes the plastic slip.
  c.edge_length = 1e-3;
  const double ref0 = c.ref_t;
  commit_contact(c);
  const double elastic = -c.tan_phi * c.normal_force / c.ks;
  BOOST_TEST(std::abs(c.shear_force + c.tan_phi * c.normal_force) <= 1e-12 * c.tan_phi * c.normal_force);
  BOOST_TEST(std::abs((c.ref_t - ref0) * c.edge_length - (c.s_iter - elastic)) <= 1e-18);
  // A real reversal (shear back inside the limit) locks it again.
  dv[kV] = 4e-7;
  c.s0 = elastic;
  BOOST_TEST(judge_contact(c, lin, dv, de, false, tol));
  BOOST_TEST(static_cast<int>(c.trial) == static_cast<int>(ContactState::Locked));
}

// The ductility of a joint loaded in both modes (scene::ModeInteraction::Quadratic): each pure
// mode keeps its own μ, an even mix (r1 = r2) takes the harmonic mean, and a brittle mode (μ = 0)
// or one without strength (an infinite ratio) in the mix makes the joint brittle.
BOOST_AUTO_TEST_CASE(the_mixed_mode_ductility_is_the_harmonic_mix_of_the_modes) {
  const double tension = 10.0, shear = 20.0;
  BOOST_TEST(mixed_mode_ductility(1.3, 0.0, tension, shear) == tension);
  BOOST_TEST(mixed_mode_ductility(0.0, 1.3, tension, shear) == shear);
  BOOST_TEST(mixed_mode_ductility(0.7, 0.7, tension, shear) == 2.0 / (1.0 / tension + 1.0 / shear),
             boost::test_tools::tolerance(1e-15));
  // cos²α = 0.36, sin²α = 0.64 (ratios 0.6 and 0.8)
  BOOST_TEST(mixed_mode_ductility(0.6, 0.8, tension, shear) == 1.0 / (0.36 / tension + 0.64 / shear),
             boost::test_tools::tolerance(1e-14));
  BOOST_TEST(mixed_mode_ductility(0.6, 0.8, tension, tension) == tension, boost::test_tools::tolerance(1e-15));
  BOOST_TEST(mixed_mode_ductility(0.6, 0.8, 0.0, shear) == 0.0);
  BOOST_TEST(mixed_mode_ductility(0.0, 0.8, 0.0, shear) == shear);  // brittle tension, not loaded in it
  BOOST_TEST(mixed_mode_ductility(0.6, std::numeric_limits<double>::infinity(), tension, shear) == 0.0);
  BOOST_TEST(softening_damage(std::hypot(0.6, 0.8) * 1.5, mixed_mode_ductility(0.6, 0.8, tension, shear)) > 0.0);
}

// A softening joint's spring (Contact::damage) carries tension with (1 − D)·kn and compression
// with kn, so that a crack closes at full stiffness; its energy and the assembly's coefficients
// follow the side the latest solve found, and crossing sides asks for another solve.
BOOST_AUTO_TEST_CASE(a_damaged_joint_spring_is_weaker_in_tension_only) {
  Contact c;
  c.kn = 3.5e8;
  c.ks = 0.5 * 1.4e8;
  c.damage = 0.5;
  c.state = c.trial = ContactState::Locked;
  c.d0 = c.d_iter = 1e-6;  // open by 1 µm
  ContactLinearisation lin;
  lin.e[kU] = 1.0;  // d = d0 + D_v[u]
  const Vec6 de = Vec6::Zero();
  Vec6 dv = Vec6::Zero();
  BOOST_TEST(!judge_contact(c, lin, dv, de, true));  // bonded: stays locked, still in tension
  BOOST_TEST(c.fn_iter == -0.5 * c.kn * 1e-6);
  BOOST_TEST(contact_coefficients(c).kn_eff == 0.5 * c.kn);
  BOOST_TEST(contact_coefficients(c).fn_rhs == -0.5 * c.kn * c.d0);
  BOOST_TEST(contact_energy(c).normal == 0.5 * 0.5 * c.kn * 1e-12);
  dv[kU] = -3e-6;                                   // closes to an overlap of 2 µm
  BOOST_TEST(judge_contact(c, lin, dv, de, true));  // the side changed: solve again
  BOOST_TEST(static_cast<int>(c.trial) == static_cast<int>(ContactState::Locked));
  BOOST_TEST(c.fn_iter == c.kn * 2e-6, boost::test_tools::tolerance(1e-12));  // d = 1e-6 − 3e-6, rounded
  BOOST_TEST(contact_coefficients(c).kn_eff == c.kn);
  BOOST_TEST(contact_energy(c).normal == 0.5 * c.kn * 4e-12, boost::test_tools::tolerance(1e-12));
  BOOST_TEST(!judge_contact(c, lin, dv, de, true));  // same side: converged
  c.damage = 0.0;                                    // an undamaged spring never asks for another solve on crossing
  dv[kU] = 0.0;
  BOOST_TEST(!judge_contact(c, lin, dv, de, true));
}
