// Issue 3, test 7: a ~2000-block glued disc impacting a plate gives bit-identical history.csv and
// final geometry with 1 and 2 OpenMP threads (fixed reduction order, deterministic contacts).
#define BOOST_TEST_MODULE dda_threads
#include <boost/test/unit_test.hpp>

#include <omp.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "ddafrac/dda/run.hpp"
#include "ddafrac/dda/synthetic.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;
namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

fs::path run_with_threads(int threads, const fs::path& root, scene::IntactNodes nodes = scene::IntactNodes::Contact,
                          scene::FractureLoad load = scene::FractureLoad::JointSprings, double stress_radius = 0.0) {
  omp_set_num_threads(threads);
  const meshes::Mesh mesh = make_ring_disc_mesh(0.1, 2000);
  scene::Scene s = make_impact_scene(3.5, 1e-3);
  s.analysis.intact_nodes = nodes;
  s.analysis.fracture_load = load;
  s.analysis.fracture_stress_radius = stress_radius;
  Engine e(s, mesh);
  RunOptions o;
  o.out_dir = root / ("threads" + std::to_string(threads) + (nodes == scene::IntactNodes::Tie ? "-ties" : ""));
  o.threads = threads;
  o.max_steps = 150;
  const RunResult r = run_simulation(e, o);
  BOOST_TEST(r.exit_status == kRunCompleted, r.message);
  BOOST_TEST(r.steps == 150);
  BOOST_TEST_MESSAGE(threads << " thread(s): " << e.blocks().block_count() << " blocks, "
                             << e.contacts().contacts.size() << " contacts, CG iterations total "
                             << e.statistics().cg_total << " over " << e.statistics().solves << " solves, wall "
                             << r.wall << " s");
  std::ofstream(o.out_dir / "final.vtu") << vtu_document(e);
  return o.out_dir;
}
}  // namespace

BOOST_AUTO_TEST_CASE(one_and_two_threads_are_bit_identical) {
  const fs::path root = fs::temp_directory_path() / ("ddafrac-dda-threads-" + std::to_string(::getpid()));
  const fs::path a = run_with_threads(1, root);
  const fs::path b = run_with_threads(2, root);
  const std::string ha = slurp(a / "history.csv"), hb = slurp(b / "history.csv");
  BOOST_TEST(ha.size() > 1000u);  // 150 rows were written
  BOOST_TEST((ha == hb));
  BOOST_TEST((slurp(a / "final.vtu") == slurp(b / "final.vtu")));
  fs::remove_all(root);
}

// The same with the copies of intact fans' nodes tied and the fracture criterion on the blocks'
// stress averaged over a radius (analysis.intact_nodes, fracture_load, fracture_stress_radius).
BOOST_AUTO_TEST_CASE(one_and_two_threads_are_bit_identical_with_ties_and_the_stress_criterion) {
  const fs::path root = fs::temp_directory_path() / ("ddafrac-dda-threads-ties-" + std::to_string(::getpid()));
  constexpr double radius = 3e-3;  // m: about seven blocks of the 2000-block disc per joint
  const fs::path a = run_with_threads(1, root, scene::IntactNodes::Tie, scene::FractureLoad::BlockStress, radius);
  const fs::path b = run_with_threads(2, root, scene::IntactNodes::Tie, scene::FractureLoad::BlockStress, radius);
  const std::string ha = slurp(a / "history.csv"), hb = slurp(b / "history.csv");
  BOOST_TEST(ha.size() > 1000u);
  BOOST_TEST((ha == hb));
  BOOST_TEST((slurp(a / "final.vtu") == slurp(b / "final.vtu")));
  fs::remove_all(root);
}
