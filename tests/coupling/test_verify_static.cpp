// Issue 6, test 1: the static Brazilian disc (plain disc, Hondros arcs 2α = 20°, P = 1 MN/m),
// the DDA twin (joints bonded and unbreakable, kn = 10 E, the study's lowest ratio, static
// mode) against the FEM (P2, one refinement) and the Hondros series, on
// scenes/small/hondros_disc.toml at about 1000 and 2000 blocks.
#define BOOST_TEST_MODULE coupling_verify_static
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <string>

#include "../fem/fixture.hpp"
#include "ddafrac/coupling/verify.hpp"
#include "ddafrac/scene/parse.hpp"
#include "ddafrac/scene/scene.hpp"

using ddafrac::test::FemEnvironment;
BOOST_TEST_GLOBAL_FIXTURE(FemEnvironment);

using namespace ddafrac;

namespace {

const std::filesystem::path scratch = std::filesystem::temp_directory_path() / "ddafrac_test_verify_static";

scene::Scene disc(int blocks) {
  auto s = scene::load_scene(std::filesystem::path(DDAFRAC_SOURCE_DIR) / "scenes" / "small" / "hondros_disc.toml");
  s.mesh.target_blocks = blocks;
  return s;
}

struct Outcome {
  coupling::VerificationReport report;
  nlohmann::json comparison;
  std::string blocks_csv;
};

Outcome run(int blocks, int threads, const std::string& tag) {
  coupling::VerifyOptions o;
  o.out_dir = scratch / tag;
  o.threads = threads;
  o.fem_degree = 2;
  o.fem_refine = 1;
  o.stiffness_ratio = 10.0;
  o.figures = false;
  o.quiet = true;
  Outcome out;
  out.report = coupling::verify_scene(disc(blocks), o);
  std::ifstream in(o.out_dir / "comparison.json");
  out.comparison = nlohmann::json::parse(in);
  std::ifstream csv(o.out_dir / "blocks.csv");
  out.blocks_csv.assign(std::istreambuf_iterator<char>(csv), {});
  return out;
}

}  // namespace

// Centre stresses (area-weighted over the blocks within R/10, every source at the same
// centroids) within 5% of the FEM and of Hondros at both meshes; the field L2 error against
// both references falls from the coarser to the finer mesh (a first-order error: by about
// 1/sqrt(2) for twice the blocks, so it must fall by at least 10%).
BOOST_AUTO_TEST_CASE(centre_stresses_and_field_error_converge) {
  const Outcome coarse = run(1000, 1, "coarse");
  const Outcome fine = run(2000, 1, "fine");
  for (const Outcome* o : {&coarse, &fine}) {
    const auto& c = o->comparison;
    BOOST_TEST_MESSAGE("blocks " << c["blocks"] << ", steps " << c["steps"] << ": centre error vs FEM "
                                 << c["centre_error_fem"] << ", vs Hondros " << c["centre_error_analytic"]
                                 << "; L2 vs FEM " << c["field_l2_fem"]["all"] << ", vs Hondros "
                                 << c["field_l2_analytic"]["all"] << "; anchor force " << c["anchor_force"]
                                 << " N/m; last step ratio " << c["last_step_ratio"]);
    BOOST_TEST(c["kn_over_E"].get<double>() == 10.0, boost::test_tools::tolerance(1e-12));
    for (int k = 0; k < 2; ++k) {
      BOOST_TEST(c["centre_error_fem"][k].get<double>() < 0.05);
      BOOST_TEST(c["centre_error_analytic"][k].get<double>() < 0.05);
    }
    // Static state reached, and the anchors carry nothing of the load.
    BOOST_TEST(c["last_step_ratio"].get<double>() < 1e-6);
    BOOST_TEST(c["anchor_force"].get<double>() < 1e-4 * c["load"].get<double>());
    // The FEM reference is far better than what it judges.
    BOOST_TEST(c["field_l2_fem_vs_analytic"].get<double>() < 0.1 * c["field_l2_fem"]["all"].get<double>());
  }
  const double b0 = coarse.comparison["blocks"].get<double>(), b1 = fine.comparison["blocks"].get<double>();
  BOOST_TEST(b0 > 900.0);
  BOOST_TEST(b1 > 1.8 * b0);
  for (const char* ref : {"field_l2_fem", "field_l2_analytic"}) {
    const double e0 = coarse.comparison[ref]["all"].get<double>(), e1 = fine.comparison[ref]["all"].get<double>();
    BOOST_TEST_MESSAGE(ref << ": " << e0 << " -> " << e1 << ", observed rate in h "
                           << std::log(e1 / e0) / std::log(std::sqrt(b0 / b1)));
    BOOST_TEST(e1 < 0.9 * e0);
  }
}

// The comparison does not depend on the DDA's thread count: every block's
// stress is the same to the last digit with 1 and 2 threads.
BOOST_AUTO_TEST_CASE(thread_count_does_not_change_the_result) {
  const Outcome one = run(600, 1, "threads1");
  const Outcome two = run(600, 2, "threads2");
  BOOST_TEST(!one.blocks_csv.empty());
  BOOST_TEST((one.blocks_csv == two.blocks_csv));
}

// A scene without the tolerances a static comparison needs is refused, naming them.
BOOST_AUTO_TEST_CASE(missing_tolerances_are_named) {
  auto s = disc(500);
  s.verification->field_l2.reset();
  const auto missing = coupling::missing_tolerances(s);
  BOOST_TEST(missing.size() == 1u);
  BOOST_TEST(missing.at(0) == "verification.field_l2");
  coupling::VerifyOptions o;
  o.out_dir = scratch / "refused";
  o.quiet = true;
  BOOST_CHECK_THROW(coupling::verify_scene(s, o), std::invalid_argument);
}
