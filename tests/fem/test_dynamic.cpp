#define BOOST_TEST_MODULE fem_dynamic
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "ddafrac/fem/dynamic_problem.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/reference/analytic.hpp"
#include "fixture.hpp"

using ddafrac::test::FemEnvironment;
BOOST_TEST_GLOBAL_FIXTURE(FemEnvironment);

using namespace ddafrac;

namespace {

constexpr double diameter = 0.1;          // m
constexpr double patch_half_angle = 0.3;  // rad: a 30 mm patch, so that the front on the axis
                                          // stays plane until the edge waves arrive
constexpr double element_size = 0.0015;   // m
constexpr double dt = 0.05e-6;            // s, c_p dt = 0.11 mm, well below h
constexpr double end_time = 15e-6;        // s, before the joint/centre reflections return
constexpr double v0 = 3.5;                // m/s
const reference::Elastic rock{10.53e9, 0.12, 2050.0};
// Gauges on the vertical diameter, d above the lowest point (0, -R).
const std::vector<double> heights{0.003, 0.010, 0.020, 0.030};

fem::DynamicProblem impact(fem::Newmark newmark) {
  meshes::ImpactDisc g;
  g.diameter = diameter;
  g.joint_angle = 0.0;
  g.connectivity = 0.25;
  g.patch_half_angle = patch_half_angle;
  fem::DynamicProblem p;
  p.mesh = meshes::generate_fem_mesh(g, element_size, meshes::FemCells::Triangles);
  p.material.elastic = rock;
  p.discretisation = {2, 0};
  p.newmark = newmark;
  p.v0 = v0;
  p.dt = dt;
  p.end_time = end_time;
  p.output_interval = dt;
  for (std::size_t i = 0; i < heights.size(); ++i)
    p.gauges.push_back({"G" + std::to_string(i), 0.0, -0.5 * diameter + heights[i]});
  return p;
}

/// syy history of one gauge.
std::vector<std::pair<double, double>> history(const fem::DynamicResult& r, std::size_t gauge) {
  std::vector<std::pair<double, double>> out;
  for (const auto& g : r.gauges)
    if (g.gauge == gauge) out.emplace_back(g.t, g.sample.stress.yy);
  return out;
}

}  // namespace

BOOST_AUTO_TEST_CASE(trapezoidal_newmark_waves_and_energy) {
  const auto r = fem::run_dynamic(impact({0.25, 0.5}));
  BOOST_TEST_MESSAGE("dofs " << r.stats.dofs << ", steps " << r.steps << ", " << r.stats.solver << ", setup "
                             << r.stats.setup_seconds << " s, run " << r.stats.solve_seconds << " s");
  const double c_p = reference::p_wave_speed(rock, reference::PlaneModel::Stress);
  const double plane = reference::impact_plane_wave_stress(rock, reference::PlaneModel::Stress, v0);

  // Arrival: first time syy passes half the plane-wave stress (the middle of the smeared front).
  for (std::size_t g = 0; g < heights.size(); ++g) {
    double arrival = -1.0;
    for (const auto& [t, syy] : history(r, g))
      if (syy < 0.5 * plane) {
        arrival = t;
        break;
      }
    const double expected = heights[g] / c_p;
    BOOST_TEST_MESSAGE("gauge at " << heights[g] * 1e3 << " mm: arrival " << arrival * 1e6 << " us, d/c_p "
                                   << expected * 1e6 << " us");
    if (g > 0) BOOST_TEST(std::abs(arrival / expected - 1.0) < 0.02);
  }

  // Plane-wave stress near the middle of the patch, after the front has passed and before the
  // edge waves (from 15 mm away) arrive.
  double sum = 0.0;
  int count = 0;
  const double from = 2.0 * heights[0] / c_p, to = 4.0 * heights[0] / c_p;
  for (const auto& [t, syy] : history(r, 0))
    if (t >= from && t <= to) {
      sum += syy;
      ++count;
    }
  const double mean = sum / count;
  BOOST_TEST_MESSAGE("syy near the patch " << mean << " Pa, -rho c_p v0 " << plane << " Pa");
  BOOST_TEST(std::abs(mean / plane - 1.0) < 0.05);

  // Energy: conserved by the trapezoidal rule once the patch is held (after the first step).
  const double e1 = r.energy[1].kinetic + r.energy[1].strain;
  double worst = 0.0;
  for (std::size_t i = 1; i < r.energy.size(); ++i)
    worst = std::max(worst, std::abs(r.energy[i].kinetic + r.energy[i].strain - e1) / e1);
  BOOST_TEST_MESSAGE("energy drift " << worst);
  BOOST_TEST(worst < 1e-3);
}

BOOST_AUTO_TEST_CASE(dda_newmark_dissipates) {
  const auto r = fem::run_dynamic(impact({0.5, 1.0}));
  const double e1 = r.energy[1].kinetic + r.energy[1].strain;
  const double e_end = r.energy.back().kinetic + r.energy.back().strain;
  BOOST_TEST_MESSAGE("(1/2, 1): energy " << e1 << " -> " << e_end << " J/m");
  BOOST_TEST(e_end < e1);  // first-order scheme with numerical damping
}

// The option of a prescribed pressure pulse on the (free) patch instead of holding it: near the
// middle of the patch the front travels along the axis as a converging cylindrical wave, so syy
// at depth d follows -sqrt(R / (R - d)) p(t - d / c_p) (the amplitude grows as the front
// converges); once the pulse has ended, the trapezoidal rule conserves the energy it put in.
BOOST_AUTO_TEST_CASE(pressure_pulse_plane_wave) {
  constexpr double peak = 10e6;            // Pa
  constexpr double duration = 4e-6;        // s: a 9 mm long half-sine, passes before edge waves
  constexpr double pulse_end_time = 8e-6;  // s
  auto p = impact({0.25, 0.5});
  p.v0 = 0.0;
  p.pulse = fem::TractionPulse{peak, duration};
  p.end_time = pulse_end_time;
  p.gauges.resize(2);  // 3 and 10 mm deep
  const auto r = fem::run_dynamic(p);
  const double c_p = reference::p_wave_speed(rock, reference::PlaneModel::Stress);
  const double radius = 0.5 * diameter;
  for (std::size_t g = 0; g < p.gauges.size(); ++g) {
    // Peak, and the centroid time of the compressive pulse (d / c_p + T / 2 if undistorted).
    double s_min = 0.0, moment = 0.0, area = 0.0;
    for (const auto& [t, syy] : history(r, g)) {
      s_min = std::min(s_min, syy);
      if (syy < 0.0) {
        moment += t * syy;
        area += syy;
      }
    }
    const double centroid = moment / area;
    const double expected_t = heights[g] / c_p + 0.5 * duration;
    const double expected_s = -peak * std::sqrt(radius / (radius - heights[g]));
    BOOST_TEST_MESSAGE("pulse, gauge at " << heights[g] * 1e3 << " mm: min syy " << s_min << " Pa (expected "
                                          << expected_s << "), centroid " << centroid * 1e6 << " us (expected "
                                          << expected_t * 1e6 << ")");
    BOOST_TEST(std::abs(s_min / expected_s - 1.0) < 0.05);
    BOOST_TEST(std::abs(centroid / expected_t - 1.0) < 0.02);
  }
  // Energy after the pulse: constant.
  double e_after = -1.0, worst = 0.0;
  for (const auto& e : r.energy) {
    if (e.t < duration + 0.5 * dt) continue;
    const double total = e.kinetic + e.strain;
    if (e_after < 0.0) e_after = total;
    worst = std::max(worst, std::abs(total / e_after - 1.0));
  }
  BOOST_TEST_MESSAGE("pulse energy " << e_after << " J/m, drift after the pulse " << worst);
  BOOST_TEST(e_after > 0.0);
  BOOST_TEST(worst < 1e-6);
}
