// Issue 6, test 2: the contact-free impact response of the DDA twin (bonded, unbreakable
// virtual joints; the impact patch held from t = 0) against the deal.II FEM of the same disc,
// on scenes/verify/impact_elastic.toml (about 1000 blocks, 60 µs).
#define BOOST_TEST_MODULE coupling_verify_dynamic
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "../fem/fixture.hpp"
#include "ddafrac/coupling/impact_runs.hpp"
#include "ddafrac/coupling/verify_dynamic.hpp"
#include "ddafrac/scene/parse.hpp"
#include "ddafrac/scene/scene.hpp"

using ddafrac::test::FemEnvironment;
BOOST_TEST_GLOBAL_FIXTURE(FemEnvironment);

using namespace ddafrac;

namespace {

scene::Scene verification_scene() {
  return scene::load_scene(std::filesystem::path(DDAFRAC_SOURCE_DIR) / "scenes" / "verify" / "impact_elastic.toml");
}

std::size_t gauge_index(const coupling::GaugeHistories& h, const std::string& name) {
  for (std::size_t g = 0; g < h.names.size(); ++g)
    if (h.names[g] == name) return g;
  BOOST_FAIL("no gauge " << name);
  return 0;
}

}  // namespace

// The whole `ddafrac verify` comparison on the scene: the P wave reaches gauges C and D
// (70 and 90 mm above the patch) within 5% of the FEM's arrival, and every gauge's σyy history
// is within the scene's RMS bound; the report passes against the scene's own tolerances.
BOOST_AUTO_TEST_CASE(contact_free_impact_matches_the_fem) {
  const scene::Scene s = verification_scene();
  BOOST_REQUIRE(s.verification && s.verification->arrival_time && s.verification->gauge_rms);
  coupling::VerifyOptions options;
  options.out_dir = std::filesystem::temp_directory_path() / "ddafrac_test_verify_dynamic";
  options.figures = false;
  const auto report = coupling::verify_dynamic(s, options);
  BOOST_TEST_MESSAGE(report.markdown);

  std::ifstream errors(options.out_dir / "impact_gauge_errors.csv");
  std::string header, line;
  std::getline(errors, header);
  int rows = 0, arrivals_within_5_percent = 0;
  while (std::getline(errors, line)) {
    ++rows;
    // gauge,x,y,fem_peak,fem_peak_t,dda_peak,dda_peak_t,peak_error,fem_arr,dda_arr,arrival_error,checked,rms,...
    std::vector<std::string> cells;
    std::size_t start = 0;
    for (std::size_t comma; (comma = line.find(',', start)) != std::string::npos; start = comma + 1)
      cells.push_back(line.substr(start, comma - start));
    cells.push_back(line.substr(start));
    BOOST_REQUIRE_EQUAL(cells.size(), 15u);
    const double arrival_error = std::stod(cells[10]);
    const double rms = std::stod(cells[12]);
    BOOST_TEST_MESSAGE("gauge " << cells[0] << ": arrival error " << arrival_error << ", RMS/peak " << rms);
    BOOST_TEST(rms < *s.verification->gauge_rms, "gauge " << cells[0] << " RMS/peak " << rms);
    if ((cells[0] == "C" || cells[0] == "D") && std::abs(arrival_error) < 0.05) ++arrivals_within_5_percent;
  }
  BOOST_TEST(rows == 8);
  BOOST_TEST(arrivals_within_5_percent == 2);
  BOOST_TEST(report.passed());
  BOOST_TEST(report.dda_wall > 0.0);
  BOOST_TEST(report.fem_wall > 0.0);
}

// Results do not depend on the thread count: 1 and 2 threads give identical gauge histories.
BOOST_AUTO_TEST_CASE(dda_twin_is_independent_of_the_thread_count) {
  const scene::Scene s = verification_scene();
  coupling::ImpactSettings settings;
  settings.max_steps = 60;
  settings.threads = 1;
  const auto one = coupling::run_impact_dda(s, settings);
  settings.threads = 2;
  const auto two = coupling::run_impact_dda(s, settings);
  BOOST_REQUIRE_EQUAL(one.steps, 60);
  for (const char* name : {"A", "B", "E", "H"}) {
    const std::size_t g = gauge_index(one, name);
    BOOST_TEST(one.syy[g].v == two.syy[g].v);
    BOOST_TEST(one.s1[g].v == two.s1[g].v);
  }
  // The wave has reached gauge A (5 mm above the patch) within these 6 µs.
  BOOST_TEST(one.syy[gauge_index(one, "A")].v.back() < -1e6);
}
