#define BOOST_TEST_MODULE fem_static_cases
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/fem/static_problem.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/reference/analytic.hpp"
#include "fixture.hpp"

using ddafrac::test::FemEnvironment;
BOOST_TEST_GLOBAL_FIXTURE(FemEnvironment);

using namespace ddafrac;

namespace {

constexpr double pi = ddafrac::common::kPi;
constexpr double diameter = 0.1;                  // m
constexpr double flat_angle = 20.0 * pi / 180.0;  // central angle of each flat
constexpr double element_size = 0.006;            // m, coarse gmsh mesh; refined by deal.II
constexpr double pressure = 50.0e6;               // Pa on the top flat
const reference::Elastic rock{10.53e9, 0.12, 2050.0};

fem::StaticProblem flattened(fem::StaticLoad load, int refinements) {
  meshes::FlattenedDisc g;
  g.diameter = diameter;
  g.flat_angle = flat_angle;
  g.with_platens = false;
  fem::StaticProblem p;
  p.mesh = meshes::generate_fem_mesh(g, element_size, meshes::FemCells::Triangles);
  p.material.elastic = rock;
  p.load = load;
  p.discretisation = {2, refinements};
  return p;
}

}  // namespace

BOOST_AUTO_TEST_CASE(flattened_disc_pressure_balances_reaction) {
  const auto solution = fem::solve_static(flattened(fem::FlatLoad{pressure, 0.0}, 2));
  const auto applied = solution.applied_force("flat_top");
  const auto reaction = solution.boundary_force("flat_bottom");
  const double flat_width = diameter * std::sin(0.5 * flat_angle);
  const double load = pressure * flat_width;  // N/m
  // The flat is straight: the quadrature of a uniform pressure is exact to round-off.
  BOOST_TEST(std::abs(-applied[1] / load - 1.0) < 1e-12);
  BOOST_TEST(std::abs(applied[0]) < 1e-12 * load);
  // Consistent nodal reactions balance the load to the solver tolerance (1e-10 relative).
  BOOST_TEST(std::abs(reaction[1] / load - 1.0) < 1e-6);
  BOOST_TEST(std::abs(reaction[0]) < 1e-6 * load);

  const auto centre = solution.stress_at(0.0, 0.0).stress;
  const auto arc = reference::flattened_disc_centre_arc_mapped({diameter, 1.0}, load, flat_angle);
  const double dxx = centre.xx / arc.xx - 1.0, dyy = centre.yy / arc.yy - 1.0;
  BOOST_TEST_MESSAGE("flattened disc: dofs " << solution.stats().dofs << ", centre sxx " << centre.xx << " (arc-mapped "
                                             << arc.xx << ", " << 100 * dxx << "%), syy " << centre.yy
                                             << " (arc-mapped " << arc.yy << ", " << 100 * dyy << "%)");
  // The arc-mapped approximation is a few percent off a flat load (different load shape);
  // a larger gap would mean a wrong load or support.
  BOOST_TEST(std::abs(dxx) < 0.05);
  BOOST_TEST(std::abs(dyy) < 0.05);
}

BOOST_AUTO_TEST_CASE(flattened_disc_prescribed_displacement) {
  constexpr double displacement = 50e-6;  // m, top flat pushed down
  const auto solution = fem::solve_static(flattened(fem::FlatLoad{0.0, displacement}, 1));
  const auto top = solution.boundary_force("flat_top");
  const auto bottom = solution.boundary_force("flat_bottom");
  BOOST_TEST_MESSAGE("displacement-controlled flat load: " << bottom[1] << " N/m");
  BOOST_TEST(bottom[1] > 0.0);
  BOOST_TEST(std::abs(top[1] + bottom[1]) < 1e-6 * bottom[1]);
}

BOOST_AUTO_TEST_CASE(slit_disc_tip_concentration_and_far_field) {
  meshes::SlitDisc g;
  g.diameter = diameter;
  g.slit = {0.025, 0.0004, 30.0 * pi / 180.0};
  const auto mesh = meshes::generate_fem_mesh(g, 0.008, meshes::FemCells::Triangles);
  const double c = std::cos(g.slit.inclination), s = std::sin(g.slit.inclination);
  // Just outside a corner of a slit end (in the material), and a point far from the slit.
  constexpr double offset = 1e-7;  // m
  const double along = 0.5 * g.slit.length + offset, across = 0.5 * g.slit.width + offset;
  std::vector<double> tip_s1, far_syy;  // tip: largest principal magnitude
  for (int k = 0; k <= 2; ++k) {
    fem::StaticProblem p;
    p.mesh = mesh;
    p.material.elastic = rock;
    p.load = fem::ArcPressure{pressure, 10.0 * pi / 180.0};
    p.discretisation = {2, k};
    const auto solution = fem::solve_static(p);
    const auto corner = solution.stress_at(along * c - across * s, along * s + across * c);
    tip_s1.push_back(std::max(std::abs(corner.s1), std::abs(corner.s3)));
    far_syy.push_back(solution.stress_at(0.03, -0.01).stress.yy);
    BOOST_TEST_MESSAGE("slit disc k=" << k << " dofs " << solution.stats().dofs << " tip |s|max " << tip_s1.back()
                                      << " far syy " << far_syy.back());
  }
  // The sharp slot corners are singular: the tip stress keeps growing with refinement.
  BOOST_TEST(tip_s1[1] > tip_s1[0]);
  BOOST_TEST(tip_s1[2] > tip_s1[1]);
  // Away from it the field converges: successive changes shrink, the last below 0.5%.
  const double change1 = std::abs(far_syy[1] - far_syy[0]), change2 = std::abs(far_syy[2] - far_syy[1]);
  BOOST_TEST(change2 < 0.5 * change1);
  BOOST_TEST(change2 < 5e-3 * std::abs(far_syy[2]));
}
