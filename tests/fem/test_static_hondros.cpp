#define BOOST_TEST_MODULE fem_static_hondros
#include <boost/test/unit_test.hpp>

#include <chrono>
#include <cmath>
#include <iostream>
#include <vector>

#include "ddafrac/fem/static_problem.hpp"
#include "ddafrac/reference/analytic.hpp"
#include "disc_mesh.hpp"
#include "fixture.hpp"

using ddafrac::test::FemEnvironment;
BOOST_TEST_GLOBAL_FIXTURE(FemEnvironment);

using namespace ddafrac;

namespace {

constexpr double diameter = 0.1;                             // m, the study's disc
constexpr double half_angle = 10.0 * test::test_pi / 180.0;  // 2 alpha = 20 deg
constexpr double load = 1.0e6;                               // N/m, nominal Hondros load P
constexpr int coarse_rings = 6;                              // rim node every 10 deg: arc ends are nodes
constexpr int profile_points = 201;

const reference::Disc disc{diameter, 1.0};
const reference::HondrosLoad hondros{load, half_angle};

fem::StaticProblem problem(bool quads, int degree, int refinements) {
  fem::StaticProblem p;
  p.mesh = test::ring_disc(disc.radius(), coarse_rings, half_angle);
  if (quads) p.mesh = test::split_into_quads(p.mesh, disc.radius());
  p.material.elastic = {10.53e9, 0.12, 2050.0};
  p.load = fem::ArcPressure{hondros.pressure(disc), half_angle};
  p.discretisation = {degree, refinements};
  return p;
}

struct Errors {
  double centre_xx, centre_yy;  // relative
  double loaded, horizontal;    // relative L2 along the diameters
  double seconds;
  std::size_t dofs;
};

/// Relative L2 error of (sxx, syy, txy) along a diameter, sampled uniformly.
template <typename Exact>
double profile_error(const std::vector<fem::StressSample>& fe, Exact exact, bool vertical) {
  double num = 0.0, den = 0.0;
  for (const auto& s : fe) {
    const reference::Stress2 e = exact(vertical ? s.y : s.x);
    num += std::pow(s.stress.xx - e.xx, 2) + std::pow(s.stress.yy - e.yy, 2) + std::pow(s.stress.xy, 2);
    den += e.xx * e.xx + e.yy * e.yy;
  }
  return std::sqrt(num / den);
}

Errors run(bool quads, int degree, int refinements) {
  const auto start = std::chrono::steady_clock::now();
  const auto solution = fem::solve_static(problem(quads, degree, refinements));
  const double r = disc.radius();
  const auto c = solution.stress_at(0.0, 0.0);
  const auto exact_c = reference::hondros_centre(disc, hondros);
  // The loaded diameter excluding the loaded arcs (|y| > R cos alpha).
  const double y_max = r * std::cos(half_angle);
  const auto vertical = solution.profile(0.0, -y_max, 0.0, y_max, profile_points);
  const auto horizontal = solution.profile(-r, 0.0, r, 0.0, profile_points);
  Errors e;
  e.centre_xx = std::abs(c.stress.xx / exact_c.xx - 1.0);
  e.centre_yy = std::abs(c.stress.yy / exact_c.yy - 1.0);
  e.loaded = profile_error(
      vertical, [](double y) { return reference::hondros_loaded_diameter(disc, hondros, y); }, true);
  e.horizontal = profile_error(
      horizontal, [](double x) { return reference::hondros_horizontal_diameter(disc, hondros, x); }, false);
  e.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  e.dofs = solution.stats().dofs;
  BOOST_TEST_MESSAGE((quads ? "quad" : "tri ")
                     << " p=" << degree << " k=" << refinements << " dofs=" << e.dofs
                     << " cg=" << solution.stats().iterations << " centre sxx " << e.centre_xx << " syy " << e.centre_yy
                     << " L2 loaded " << e.loaded << " horizontal " << e.horizontal << " time " << e.seconds << " s");
  return e;
}

double order(double coarse, double fine) { return std::log2(coarse / fine); }

}  // namespace

/// Runs refinements 0..levels, logs the observed orders and returns the errors.
std::vector<Errors> study(bool quads, int degree, int levels) {
  std::vector<Errors> e;
  for (int k = 0; k <= levels; ++k) e.push_back(run(quads, degree, k));
  for (std::size_t i = 1; i < e.size(); ++i)
    BOOST_TEST_MESSAGE("  observed order: loaded " << order(e[i - 1].loaded, e[i].loaded) << ", horizontal "
                                                   << order(e[i - 1].horizontal, e[i].horizontal) << ", centre sxx "
                                                   << order(e[i - 1].centre_xx, e[i].centre_xx));
  return e;
}

// Stress errors of degree p fall as h^p (the arc-end singularities are outside the profiles
// and only pollute at higher order). Orders are asserted on the two finest pairs with a margin
// of 0.2 below the expected value.
constexpr double order_margin = 0.2;

BOOST_AUTO_TEST_CASE(triangles_degree2) {
  const auto e = study(false, 2, 3);
  const Errors& fine = e.back();
  BOOST_TEST(fine.centre_xx < 1e-3);  // issue 5: within 0.1% of the closed form
  BOOST_TEST(fine.centre_yy < 1e-3);
  BOOST_TEST(fine.loaded < 5e-3);  // relative L2 along the diameters below 0.5%
  BOOST_TEST(fine.horizontal < 5e-3);
  for (std::size_t i = e.size() - 2; i < e.size(); ++i) {
    BOOST_TEST(order(e[i - 1].loaded, e[i].loaded) > 2.0 - order_margin);
    BOOST_TEST(order(e[i - 1].horizontal, e[i].horizontal) > 2.0 - order_margin);
  }
}

BOOST_AUTO_TEST_CASE(triangles_degree1) {
  const auto e = study(false, 1, 3);
  for (std::size_t i = e.size() - 2; i < e.size(); ++i) {
    BOOST_TEST(order(e[i - 1].loaded, e[i].loaded) > 1.0 - 2 * order_margin);
    BOOST_TEST(order(e[i - 1].horizontal, e[i].horizontal) > 1.0 - order_margin);
  }
}

BOOST_AUTO_TEST_CASE(quads_degree2) {
  const auto e = study(true, 2, 2);
  const Errors& fine = e.back();
  BOOST_TEST(fine.centre_xx < 1e-3);
  BOOST_TEST(fine.centre_yy < 1e-3);
  BOOST_TEST(fine.loaded < 5e-3);
  BOOST_TEST(fine.horizontal < 5e-3);
  BOOST_TEST(order(e[1].loaded, e[2].loaded) > 2.0 - order_margin);
  BOOST_TEST(order(e[1].horizontal, e[2].horizontal) > 2.0 - order_margin);
}

// The horizontal error of bilinear quads is pre-asymptotic up to k = 2 (order 0.5 from k = 1
// to 2, then 1.1): the order is asserted on the finest pair only.
BOOST_AUTO_TEST_CASE(quads_degree1) {
  const auto e = study(true, 1, 3);
  BOOST_TEST(order(e[2].loaded, e[3].loaded) > 1.0 - order_margin);
  BOOST_TEST(order(e[2].horizontal, e[3].horizontal) > 1.0 - order_margin);
}
