#define BOOST_TEST_MODULE coupling_analytic
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/reference/analytic.hpp"

using namespace ddafrac::reference;

namespace {
constexpr double pi = ddafrac::common::kPi;
const Disc disc{0.1, 1.0};
constexpr double load = 1.0e6;  // N/m

double rel(double a, double b) { return std::abs(a - b) / std::abs(b); }
}  // namespace

BOOST_AUTO_TEST_CASE(point_load_centre_and_free_rim) {
  const Stress2 c = point_load_stress(disc, load, 0.0, 0.0);
  const double scale = 2.0 * load / (pi * disc.diameter * disc.thickness);
  BOOST_TEST(rel(c.xx, scale) < 1e-14);
  BOOST_TEST(rel(c.yy, -3.0 * scale) < 1e-14);
  BOOST_TEST(std::abs(c.xy) < 1e-9 * scale);
  // Traction-free rim away from the loads: sigma . n = 0 (round-off level).
  for (double a : {0.1, 0.7, 1.3, 2.9, 4.0, 5.5}) {
    const double r = disc.radius(), nx = std::cos(a), ny = std::sin(a);
    const Stress2 s = point_load_stress(disc, load, r * nx, r * ny);
    BOOST_TEST(std::abs(s.xx * nx + s.xy * ny) < 1e-9 * scale);
    BOOST_TEST(std::abs(s.xy * nx + s.yy * ny) < 1e-9 * scale);
  }
}

BOOST_AUTO_TEST_CASE(hondros_centre_closed_form) {
  const HondrosLoad h{load, 10.0 * pi / 180.0};
  const double p = h.pressure(disc);
  BOOST_TEST(rel(p, load / (2.0 * h.half_angle * disc.radius())) < 1e-15);
  const Stress2 c = hondros_centre(disc, h);
  const double a = h.half_angle;
  BOOST_TEST(rel(c.xx, 2.0 * p / pi * (std::sin(2 * a) - a)) < 1e-14);
  BOOST_TEST(rel(c.yy, -2.0 * p / pi * (std::sin(2 * a) + a)) < 1e-14);
  // 2 alpha = 20 deg: centre sxx is 0.9798 of the point-load value 2P/(pi D t).
  BOOST_TEST(rel(c.xx / (2.0 * load / (pi * disc.diameter)), (std::sin(2 * a) - a) / a) < 1e-14);
}

BOOST_AUTO_TEST_CASE(hondros_tends_to_point_load) {
  // alpha -> 0: the relative difference is O((alpha / (1 - rho^2))^2), largest near the loads.
  const HondrosLoad h{load, 1e-4};
  for (double t : {-0.8, -0.3, 0.0, 0.5, 0.9}) {
    const double y = t * disc.radius();
    const double tol = 1000.0 * std::pow(h.half_angle / (1.0 - t * t), 2);
    const Stress2 hv = hondros_loaded_diameter(disc, h, y);
    const Stress2 pv = point_load_stress(disc, load, 0.0, y);
    BOOST_TEST(rel(hv.xx, pv.xx) < tol);
    BOOST_TEST(rel(hv.yy, pv.yy) < tol);
    const Stress2 hh = hondros_horizontal_diameter(disc, h, y);
    const Stress2 ph = point_load_stress(disc, load, y, 0.0);
    BOOST_TEST(rel(hh.xx, ph.xx) < tol);
    BOOST_TEST(rel(hh.yy, ph.yy) < tol);
  }
}

BOOST_AUTO_TEST_CASE(series_matches_closed_forms_and_superposition) {
  const HondrosLoad h{load, 10.0 * pi / 180.0};
  const double scale = h.pressure(disc);
  for (double t : {-0.95, -0.6, -0.2, 0.0, 0.3, 0.7, 0.95}) {
    const double v = t * disc.radius();
    const Stress2 sv = hondros_series(disc, h, 0.0, v), cv = hondros_loaded_diameter(disc, h, v);
    const Stress2 sh = hondros_series(disc, h, v, 0.0), ch = hondros_horizontal_diameter(disc, h, v);
    BOOST_TEST(std::abs(sv.xx - cv.xx) < 1e-12 * scale);
    BOOST_TEST(std::abs(sv.yy - cv.yy) < 1e-12 * scale);
    BOOST_TEST(std::abs(sv.xy) < 1e-12 * scale);
    BOOST_TEST(std::abs(sh.xx - ch.xx) < 1e-12 * scale);
    BOOST_TEST(std::abs(sh.yy - ch.yy) < 1e-12 * scale);
  }
  // Off the diameters (incl. the shear sign): series vs superposition of rim forces. The
  // 400-point Gauss rule is exact to round-off for points >= 0.1 R from the arcs.
  for (const auto& [x, y] : {std::pair{0.02, 0.01}, {-0.03, 0.025}, {0.035, -0.02}, {-0.01, -0.04}}) {
    const Stress2 s = hondros_series(disc, h, x, y), q = hondros_superposition(disc, h, x, y);
    BOOST_TEST(std::abs(s.xx - q.xx) < 1e-10 * scale);
    BOOST_TEST(std::abs(s.yy - q.yy) < 1e-10 * scale);
    BOOST_TEST(std::abs(s.xy - q.xy) < 1e-10 * scale);
    BOOST_TEST(std::abs(s.xy) > 1e-3 * scale);  // the shear check is not vacuous
  }
}

BOOST_AUTO_TEST_CASE(series_is_in_equilibrium) {
  // d sxx/dx + d sxy/dy = 0 and d sxy/dx + d syy/dy = 0 (central differences, O(h^2) ~ 1e-7 p/R).
  const HondrosLoad h{load, 10.0 * pi / 180.0};
  const double p = h.pressure(disc), d = 1e-5;
  for (const auto& [x, y] : {std::pair{0.01, 0.02}, {-0.02, -0.015}}) {
    const auto sx1 = hondros_series(disc, h, x + d, y), sx0 = hondros_series(disc, h, x - d, y);
    const auto sy1 = hondros_series(disc, h, x, y + d), sy0 = hondros_series(disc, h, x, y - d);
    const double fx = (sx1.xx - sx0.xx + sy1.xy - sy0.xy) / (2 * d);
    const double fy = (sx1.xy - sx0.xy + sy1.yy - sy0.yy) / (2 * d);
    BOOST_TEST(std::abs(fx) < 1e-5 * p / disc.radius());
    BOOST_TEST(std::abs(fy) < 1e-5 * p / disc.radius());
  }
}

BOOST_AUTO_TEST_CASE(flattened_disc_arc_mapping) {
  const double flat = 20.0 * pi / 180.0, a = 0.5 * flat;
  const Stress2 c = flattened_disc_centre_arc_mapped(disc, load, flat);
  const double p = load / (2.0 * disc.radius() * std::sin(a));
  BOOST_TEST(rel(c.xx, 2.0 * p / pi * (std::sin(2 * a) - a)) < 1e-14);
}

BOOST_AUTO_TEST_CASE(wave_speeds) {
  const Elastic rock{10.53e9, 0.12, 2050.0};
  // Plane stress c_p = sqrt(E / (rho (1 - nu^2))) = 2282.90 m/s for the rock of the study.
  BOOST_TEST(std::abs(p_wave_speed(rock, PlaneModel::Stress) - 2282.90) < 0.01);
  BOOST_TEST(p_wave_speed(rock, PlaneModel::Strain) > p_wave_speed(rock, PlaneModel::Stress));
  BOOST_TEST(rel(s_wave_speed(rock), std::sqrt(10.53e9 / (2 * 2050.0 * 1.12))) < 1e-15);
  BOOST_TEST(rel(impact_plane_wave_stress(rock, PlaneModel::Stress, 3.5),
                 -2050.0 * 3.5 * p_wave_speed(rock, PlaneModel::Stress)) < 1e-15);
  const auto pr = principal({1.0, -2.0, 0.0});
  BOOST_TEST(pr.s1 == 1.0);
  BOOST_TEST(pr.s3 == -2.0);
}
