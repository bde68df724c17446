// Issue 3, test 7: a ~2000-block glued disc impacting a plate gives bit-identical history.csv and
// final geometry with 1 and 2 OpenMP threads (fixed reduction order, deterministic contacts).
#define BOOST_TEST_MODULE dda_threads
#include <boost/test/unit_test.hpp>

#include <omp.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>

#include "ddafrac/dda/run.hpp"
#include "ddafrac/dda/synthetic.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;
namespace fs = std::filesystem;

namespace {
/// The softening variant's virtual joints: a hundredth of the source study's strength, so that
/// the first 15 µs of the impact load some past it, and G_f = 1 J/m², which lets joints of the
/// disc's ~6 mm soften (μ ≈ 40) rather than break at their strength.
constexpr double kThreadTestStrengthFactor = 0.01;
constexpr double kThreadTestFractureEnergy = 1.0;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// The scene options a run of the thread test varies from the defaults.
struct Variant {
  std::string tag;
  scene::IntactNodes nodes = scene::IntactNodes::Contact;
  scene::FractureLoad load = scene::FractureLoad::JointSprings;
  double stress_radius = 0.0;    // m, analysis.fracture_stress_radius
  double fracture_energy = 0.0;  // J/m², of the disc's virtual joints
  std::optional<double> shear_fracture_energy = std::nullopt;  // J/m², of the disc's virtual joints (mode II's own)
  scene::ModeInteraction modes = scene::ModeInteraction::None;  // of the disc's virtual joints
  double strength_factor = 1.0;  // on the tensile strength and cohesion of the disc's virtual joints
};

struct ThreadRun {
  fs::path dir;
  long softened = 0;  // intact joints with damage at the end
};

ThreadRun run_with_threads(int threads, const fs::path& root, const Variant& v = {}) {
  omp_set_num_threads(threads);
  const meshes::Mesh mesh = make_ring_disc_mesh(0.1, 2000);
  scene::Scene s = make_impact_scene(3.5, 1e-3);
  s.analysis.intact_nodes = v.nodes;
  s.analysis.fracture_load = v.load;
  s.analysis.fracture_stress_radius = v.stress_radius;
  for (const scene::Body& b : s.bodies)
    if (b.virtual_joints) {
      scene::JointSet& js = s.joint_sets[*b.virtual_joints];
      js.fracture_energy = v.fracture_energy;
      js.shear_fracture_energy = v.shear_fracture_energy;
      js.mode_interaction = v.modes;
      js.tensile_strength *= v.strength_factor;
      js.cohesion *= v.strength_factor;
    }
  Engine e(s, mesh);
  RunOptions o;
  o.out_dir = root / ("threads" + std::to_string(threads) + v.tag);
  o.threads = threads;
  o.max_steps = 150;
  const RunResult r = run_simulation(e, o);
  BOOST_TEST(r.exit_status == kRunCompleted, r.message);
  BOOST_TEST(r.steps == 150);
  ThreadRun out{o.out_dir};
  for (const Joint& j : e.blocks().joints) out.softened += !j.broken && j.damage > 0.0;
  BOOST_TEST_MESSAGE(threads << " thread(s): " << e.blocks().block_count() << " blocks, "
                             << e.contacts().contacts.size() << " contacts, CG iterations total "
                             << e.statistics().cg_total << " over " << e.statistics().solves << " solves, "
                             << e.crack_counts().total << " cracks, " << out.softened << " joints softening, wall "
                             << r.wall << " s");
  std::ofstream(o.out_dir / "final.vtu") << vtu_document(e);
  return out;
}

/// Both runs wrote the same history and final state.
void expect_identical(const fs::path& a, const fs::path& b) {
  const std::string ha = slurp(a / "history.csv"), hb = slurp(b / "history.csv");
  BOOST_TEST(ha.size() > 1000u);  // 150 rows were written
  BOOST_TEST((ha == hb));
  BOOST_TEST((slurp(a / "final.vtu") == slurp(b / "final.vtu")));
}
}  // namespace

BOOST_AUTO_TEST_CASE(one_and_two_threads_are_bit_identical) {
  const fs::path root = fs::temp_directory_path() / ("ddafrac-dda-threads-" + std::to_string(::getpid()));
  expect_identical(run_with_threads(1, root).dir, run_with_threads(2, root).dir);
  fs::remove_all(root);
}

// The same with the copies of intact fans' nodes tied and the fracture criterion on the blocks'
// stress averaged over a radius (analysis.intact_nodes, fracture_load, fracture_stress_radius).
BOOST_AUTO_TEST_CASE(one_and_two_threads_are_bit_identical_with_ties_and_the_stress_criterion) {
  const fs::path root = fs::temp_directory_path() / ("ddafrac-dda-threads-ties-" + std::to_string(::getpid()));
  Variant v;
  v.tag = "-ties";
  v.nodes = scene::IntactNodes::Tie;
  v.load = scene::FractureLoad::BlockStress;
  v.stress_radius = 3e-3;  // m: about seven blocks of the 2000-block disc per joint
  expect_identical(run_with_threads(1, root, v).dir, run_with_threads(2, root, v).dir);
  fs::remove_all(root);
}

namespace {
/// 1 and 2 threads of the softening variant `v` give the same files, with joints softening.
void expect_softening_identical(const Variant& v, const std::string& dir_name) {
  const fs::path root = fs::temp_directory_path() / (dir_name + std::to_string(::getpid()));
  const ThreadRun a = run_with_threads(1, root, v), b = run_with_threads(2, root, v);
  BOOST_TEST(a.softened > 0);  // the runs exercise the softening
  BOOST_TEST(a.softened == b.softened);
  expect_identical(a.dir, b.dir);
  fs::remove_all(root);
}
}  // namespace

// The same with softening joints (JointSet::fracture_energy): the damage is judged per joint and
// what the springs give up summed in a fixed order.
BOOST_AUTO_TEST_CASE(one_and_two_threads_are_bit_identical_with_softening_joints) {
  Variant v;
  v.tag = "-softening";
  v.fracture_energy = kThreadTestFractureEnergy;
  v.strength_factor = kThreadTestStrengthFactor;
  expect_softening_identical(v, "ddafrac-dda-threads-softening-");
}

// The same with shear softening on its own law (JointSet::shear_fracture_energy, here twice the
// tension's energy): each mode's damage is judged per joint.
BOOST_AUTO_TEST_CASE(one_and_two_threads_are_bit_identical_with_shear_softening_of_its_own) {
  Variant v;
  v.tag = "-mode2";
  v.fracture_energy = kThreadTestFractureEnergy;
  v.shear_fracture_energy = 2.0 * kThreadTestFractureEnergy;
  v.strength_factor = kThreadTestStrengthFactor;
  expect_softening_identical(v, "ddafrac-dda-threads-mode2-");
}

// The same with the two modes combined (JointSet::mode_interaction = quadratic): the mix is judged
// per joint on its own ratios.
BOOST_AUTO_TEST_CASE(one_and_two_threads_are_bit_identical_with_the_modes_combined) {
  Variant v;
  v.tag = "-mixed";
  v.fracture_energy = kThreadTestFractureEnergy;
  v.shear_fracture_energy = 2.0 * kThreadTestFractureEnergy;
  v.modes = scene::ModeInteraction::Quadratic;
  v.strength_factor = kThreadTestStrengthFactor;
  expect_softening_identical(v, "ddafrac-dda-threads-mixed-");
}
