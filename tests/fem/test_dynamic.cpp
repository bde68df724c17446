#define BOOST_TEST_MODULE fem_dynamic
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "ddafrac/coupling/analytic.hpp"
#include "ddafrac/fem/dynamic_problem.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "fixture.hpp"

using ddafrac::test::FemEnvironment;
BOOST_TEST_GLOBAL_FIXTURE(FemEnvironment);

using namespace ddafrac;

namespace {

constexpr double diameter = 0.1;            // m
constexpr double patch_half_angle = 0.3;    // rad: a 30 mm patch, so that the front on the axis
                                            // stays plane until the edge waves arrive
constexpr double element_size = 0.0015;     // m
constexpr double dt = 0.05e-6;              // s, c_p dt = 0.11 mm, well below h
constexpr double end_time = 15e-6;          // s, before the joint/centre reflections return
constexpr double v0 = 3.5;                  // m/s
const coupling::Elastic rock{10.53e9, 0.12, 2050.0};
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
  BOOST_TEST_MESSAGE("dofs " << r.stats.dofs << ", steps " << r.steps << ", CG iterations "
                     << r.stats.iterations << ", setup " << r.stats.setup_seconds << " s, run "
                     << r.stats.solve_seconds << " s");
  const double c_p = coupling::p_wave_speed(rock, coupling::PlaneModel::Stress);
  const double plane = coupling::impact_plane_wave_stress(rock, coupling::PlaneModel::Stress, v0);

  // Arrival: first time syy passes half the plane-wave stress (the middle of the smeared front).
  for (std::size_t g = 0; g < heights.size(); ++g) {
    double arrival = -1.0;
    for (const auto& [t, syy] : history(r, g))
      if (syy < 0.5 * plane) {
        arrival = t;
        break;
      }
    const double expected = heights[g] / c_p;
    BOOST_TEST_MESSAGE("gauge at " << heights[g] * 1e3 << " mm: arrival " << arrival * 1e6
                       << " us, d/c_p " << expected * 1e6 << " us");
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
