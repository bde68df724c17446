// Crack metrics (crack_metrics.hpp): fragments, crack length, largest fragment and the first
// (through-going) crack on a glued grid with joints broken by hand or by hand-made crack events,
// where every number is known exactly; and on a disc that cracks under impact, the history
// built from the events against the joints' state and the engine's counts.
#define BOOST_TEST_MODULE dda_crack_metrics
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <utility>
#include <vector>

#include "ddafrac/dda/crack_metrics.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/dda/synthetic.hpp"
#include "support.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;

namespace {

constexpr int kCells = 4;                    // the grid is kCells × kCells squares
constexpr double kSide = 0.25;               // m, a square's side: a power of two, so every sum below is exact
constexpr double kCellArea = kSide * kSide;  // m²
constexpr double kBodyArea = kCells * kCells * kCellArea;  // m²

/// One body of kCells × kCells squares sharing their nodes (block = row · kCells + column),
/// glued by virtual joints: 2 · kCells · (kCells − 1) joints.
BlockSystem glued_grid() {
  scene::Scene s = testing::basic_scene(scene::Mode::Dynamic, 1e-6, 1e9, {0.0, 0.0});
  scene::JointSet bonded;
  bonded.name = "virtual";
  s.joint_sets.push_back(bonded);
  scene::Body rock = testing::body("rock");
  rock.virtual_joints = 1;
  s.bodies.push_back(rock);
  meshes::Mesh m;
  m.body_names = {"rock"};
  for (int r = 0; r <= kCells; ++r)
    for (int c = 0; c <= kCells; ++c) m.nodes.push_back({c * kSide, r * kSide});
  const auto node = [](int r, int c) { return static_cast<meshes::Index>(r * (kCells + 1) + c); };
  m.cell_offsets = {0};
  for (int r = 0; r < kCells; ++r)
    for (int c = 0; c < kCells; ++c) {
      for (const meshes::Index n : {node(r, c), node(r, c + 1), node(r + 1, c + 1), node(r + 1, c)})
        m.cell_nodes.push_back(n);
      m.cell_offsets.push_back(static_cast<meshes::Index>(m.cell_nodes.size()));
      m.cell_body.push_back(0);
    }
  return build_block_system(s, m, true);
}

Index block(int row, int column) { return static_cast<Index>(row * kCells + column); }

/// The joint between two blocks.
Index joint(const BlockSystem& b, Index p, Index q) {
  for (std::size_t k = 0; k < b.joints.size(); ++k)
    if (b.joints[k].block_a == std::min(p, q) && b.joints[k].block_b == std::max(p, q)) return static_cast<Index>(k);
  BOOST_FAIL("no joint between blocks " << p << " and " << q);
  return -1;
}

/// The joints that cut the bottom-left block off: 2 joints.
std::vector<Index> corner_cut(const BlockSystem& b) {
  return {joint(b, block(0, 0), block(0, 1)), joint(b, block(0, 0), block(1, 0))};
}

/// The joints of the vertical line x = 2·kSide, which cuts the grid in halves: kCells joints.
std::vector<Index> vertical_cut(const BlockSystem& b) {
  std::vector<Index> cut;
  for (int r = 0; r < kCells; ++r) cut.push_back(joint(b, block(r, 1), block(r, 2)));
  return cut;
}

void break_by_hand(BlockSystem& b, const std::vector<Index>& joints, CrackType type) {
  for (const Index k : joints) {
    b.joints[static_cast<std::size_t>(k)].broken = true;
    b.joints[static_cast<std::size_t>(k)].failure = type;
  }
}

}  // namespace

BOOST_AUTO_TEST_CASE(an_intact_glued_grid_is_one_fragment_with_no_crack) {
  const BlockSystem b = glued_grid();
  BOOST_REQUIRE(b.joints.size() == 2u * kCells * (kCells - 1));
  const CrackHistory h = crack_history(b, {});
  BOOST_REQUIRE(h.now.size() == 1u);
  const BodyCracks& body = h.now[0];
  BOOST_TEST(body.body == 0);
  BOOST_TEST(body.area == kBodyArea);
  BOOST_TEST(body.fragments == 1);
  BOOST_TEST(body.through_fragments == 1);
  BOOST_TEST(body.largest_fragment_area == kBodyArea);
  BOOST_TEST(body.cracks_tensile + body.cracks_shear + body.cracks_untyped == 0);
  BOOST_TEST(body.length_tensile + body.length_shear == 0.0);
  BOOST_TEST(!h.first_crack[0]);
  BOOST_TEST(!h.first_through_crack[0]);
}

// A chipped corner is a second fragment but not a through-going crack (1/16 of the area is
// below kThroughCrackFragmentFraction); cutting the rest in two is one.
BOOST_AUTO_TEST_CASE(joints_broken_by_hand_give_the_fragments_areas_and_lengths_they_cut) {
  static_assert(kCellArea < kThroughCrackFragmentFraction * kBodyArea, "the corner must be too small to count");
  BlockSystem b = glued_grid();
  break_by_hand(b, corner_cut(b), CrackType::Tensile);
  {
    const BodyCracks body = crack_history(b, {}).now[0];
    BOOST_TEST(body.fragments == 2);
    BOOST_TEST(body.through_fragments == 1);
    BOOST_TEST(body.largest_fragment_area == kBodyArea - kCellArea);
    BOOST_TEST(body.cracks_tensile == 2);
    BOOST_TEST(body.length_tensile == 2 * kSide);
  }
  break_by_hand(b, vertical_cut(b), CrackType::Shear);
  const CrackHistory h = crack_history(b, {});
  const BodyCracks& body = h.now[0];
  BOOST_TEST(body.fragments == 3);  // the corner, the rest of the left half, the right half
  BOOST_TEST(body.through_fragments == 2);
  BOOST_TEST(body.largest_fragment_area == kBodyArea / 2);
  BOOST_TEST(body.cracks_tensile == 2);
  BOOST_TEST(body.cracks_shear == kCells);
  BOOST_TEST(body.length_tensile == 2 * kSide);
  BOOST_TEST(body.length_shear == kCells * kSide);
  BOOST_TEST(*h.first_crack[0] == 0.0);  // broken with no event: broken from the start
  BOOST_TEST(*h.first_through_crack[0] == 0.0);
}

// The same cuts as crack events at known times: the history at requested times, the first
// crack at the first event and the through-going crack when the last joint of the line breaks,
// not before (a line with one joint left still holds the halves together).
BOOST_AUTO_TEST_CASE(crack_events_give_the_history_and_the_first_through_going_crack) {
  BlockSystem b = glued_grid();
  constexpr double kCornerTime = 1e-6, kLineStart = 2e-6, kLineStep = 1e-6;  // s
  std::vector<CrackEvent> events;
  const auto event = [&](double t, Index k, CrackType type) {
    events.push_back({t, 0.0, 0.0, type, k, 0.0, 0.0});
    b.joints[static_cast<std::size_t>(k)].broken = true;
    b.joints[static_cast<std::size_t>(k)].failure = type;
  };
  for (const Index k : corner_cut(b)) event(kCornerTime, k, CrackType::Tensile);  // both in one step
  const std::vector<Index> line = vertical_cut(b);
  for (std::size_t i = 0; i < line.size(); ++i)
    event(kLineStart + static_cast<double>(i) * kLineStep, line[i], CrackType::Shear);
  const double last = kLineStart + (kCells - 1) * kLineStep;  // s, the line's last joint

  const std::vector<double> times = {last, 0.0, kCornerTime, last - kLineStep / 2};  // any order
  const CrackHistory h = crack_history(b, events, times);
  BOOST_TEST(*h.first_crack[0] == kCornerTime);
  BOOST_TEST(*h.first_through_crack[0] == last);

  const BodyCracks& at_start = h.at_times[1][0];
  BOOST_TEST(at_start.fragments == 1);
  BOOST_TEST(at_start.cracks_tensile + at_start.cracks_shear == 0);
  const BodyCracks& after_corner = h.at_times[2][0];
  BOOST_TEST(after_corner.fragments == 2);
  BOOST_TEST(after_corner.cracks_tensile == 2);
  BOOST_TEST(after_corner.largest_fragment_area == kBodyArea - kCellArea);
  const BodyCracks& line_almost = h.at_times[3][0];
  BOOST_TEST(line_almost.fragments == 2);
  BOOST_TEST(line_almost.cracks_shear == kCells - 1);
  BOOST_TEST(line_almost.length_shear == (kCells - 1) * kSide);
  BOOST_TEST(line_almost.through_fragments == 1);
  const BodyCracks& at_end = h.at_times[0][0];
  BOOST_TEST(at_end.fragments == 3);
  BOOST_TEST(at_end.through_fragments == 2);
  BOOST_TEST(at_end.largest_fragment_area == kBodyArea / 2);

  // Now (after every event) is the state at the last event, and the one the joints' flags give.
  const BodyCracks from_flags = crack_history(b, {}).now[0];
  for (const BodyCracks* s : {&h.now[0], &from_flags}) {
    BOOST_TEST(s->fragments == at_end.fragments);
    BOOST_TEST(s->largest_fragment_area == at_end.largest_fragment_area);
    BOOST_TEST(s->length_shear == at_end.length_shear);
  }
}

// A disc hitting a plate at 20 m/s with joints at 5% of their strength cracks within 200 steps.
// The history from its crack events ends where its joints' flags are: the same fragments, the
// crack counts of the engine, the same crack length (summed in another order: round-off only);
// and counts, lengths and the largest fragment never go the wrong way in time.
BOOST_AUTO_TEST_CASE(the_history_of_a_cracking_disc_ends_at_its_joints_state) {
  scene::Scene s = make_impact_scene(20.0, 1e-3);
  constexpr double kWeakening = 0.05;  // of the virtual joints' strengths
  for (auto& js : s.joint_sets) {
    js.tensile_strength *= kWeakening;
    js.cohesion *= kWeakening;
  }
  Engine e(s, make_ring_disc_mesh(0.1, 600));
  constexpr int kSteps = 200;
  for (int k = 0; k < kSteps; ++k) e.step();
  BOOST_REQUIRE(e.crack_counts().total > 0);

  std::vector<double> times;
  constexpr int kSamples = 20;
  for (int k = 0; k < kSamples; ++k) times.push_back(e.time() * k / kSamples);
  times.push_back(e.time());
  const CrackHistory h = crack_history(e.blocks(), e.cracks(), times);
  const CrackHistory flags = crack_history(e.blocks(), {});
  BOOST_REQUIRE(h.now.size() == 1u);  // the disc; the plate has no joints
  const BodyCracks& now = h.now[0];
  BOOST_TEST(now.cracks_tensile == e.crack_counts().tensile);
  BOOST_TEST(now.cracks_shear == e.crack_counts().shear);
  BOOST_TEST(now.cracks_untyped == 0);
  BOOST_TEST(now.fragments == flags.now[0].fragments);
  BOOST_TEST(now.through_fragments == flags.now[0].through_fragments);
  constexpr double kRoundOff = 1e-12;  // relative: sums of a few hundred lengths in another order
  BOOST_TEST(std::abs(now.length_tensile - flags.now[0].length_tensile) <= kRoundOff * now.length_tensile);
  BOOST_TEST(std::abs(now.length_shear - flags.now[0].length_shear) <= kRoundOff * now.length_shear);
  BOOST_TEST(*h.first_crack[0] == e.cracks().front().t);
  for (std::size_t k = 1; k < times.size(); ++k) {
    const BodyCracks& a = h.at_times[k - 1][0];
    const BodyCracks& b = h.at_times[k][0];
    BOOST_TEST(b.cracks_tensile >= a.cracks_tensile);
    BOOST_TEST(b.cracks_shear >= a.cracks_shear);
    BOOST_TEST(b.length_tensile >= a.length_tensile);
    BOOST_TEST(b.fragments >= a.fragments);
    BOOST_TEST(b.largest_fragment_area <= a.largest_fragment_area);
  }
  BOOST_TEST(h.at_times.back()[0].fragments == now.fragments);
  BOOST_TEST_MESSAGE("cracks " << e.crack_counts().total << ", fragments " << now.fragments << ", largest "
                               << now.largest_fragment_area / now.area << " of the disc");
}
