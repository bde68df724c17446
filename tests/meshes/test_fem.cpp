// FEM meshes: the disc alone, triangles or all-quadrilateral, counter-clockwise, with the
// boundary groups, at the requested element size.
#define BOOST_TEST_MODULE meshes_fem
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <string>
#include <vector>

#include "ddafrac/meshes/generate.hpp"
#include "mesh_checks.hpp"

using namespace ddafrac::meshes;
using namespace ddafrac::meshes::testing;

namespace {

constexpr double kRadius = 0.05;         // m
constexpr double kAreaTolerance = 2e-3;  // relative; coarse rim at h = 4 mm loses ~ (h/R)^2/6
// A uniform mesh of size h has about area / (sqrt(3)/4 h^2) triangles; gmsh's own sizing
// deviates from this ideal by tens of percent, not by factors.
constexpr double kCountSpread = 0.5;

std::size_t cells_of_size(const Mesh& mesh, std::size_t corners) {
  std::size_t count = 0;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) count += mesh.cell_size(c) == corners;
  return count;
}

}  // namespace

BOOST_AUTO_TEST_CASE(flattened_disc_triangles_without_platens) {
  constexpr double h = 0.004;
  QualityReport report;
  const Mesh mesh = generate_fem_mesh(FlattenedDisc{}, h, FemCells::Triangles, &report);
  BOOST_TEST(mesh.body_names == std::vector<std::string>{"disc"}, boost::test_tools::per_element());
  BOOST_TEST(index_of(mesh.boundary_names, "flat_top") >= 0);
  BOOST_TEST(index_of(mesh.boundary_names, "flat_bottom") >= 0);
  BOOST_TEST(cells_of_size(mesh, 3) == mesh.cell_count());
  BOOST_TEST(smallest_relative_area(mesh) > 0.0);
  BOOST_TEST(misoriented_boundary_edges(mesh) == 0u);
  const double ideal = body_area(mesh, "disc") / (std::sqrt(3.0) / 4 * h * h);
  BOOST_TEST(std::abs(static_cast<double>(mesh.cell_count()) - ideal) <= kCountSpread * ideal);
  BOOST_TEST(report.element_size == h);
  BOOST_TEST(report.blocks == mesh.cell_count());
}

BOOST_AUTO_TEST_CASE(quadrilaterals_are_all_quads_and_counter_clockwise) {
  PlainDisc loaded;
  loaded.load_half_angle = 0.1;
  for (const Geometry& geometry : std::vector<Geometry>{loaded, FlattenedDisc{}, SlitDisc{}}) {
    for (double h : {0.002, 0.004}) {
      QualityReport report;
      const Mesh mesh = generate_fem_mesh(geometry, h, FemCells::Quadrilaterals, &report);
      BOOST_TEST(cells_of_size(mesh, 4) == mesh.cell_count());
      BOOST_TEST(smallest_relative_area(mesh) > 0.0);
      BOOST_TEST(misoriented_boundary_edges(mesh) == 0u);
      BOOST_TEST_MESSAGE("h " << h << ": " << mesh.cell_count() << " quads, min angle " << report.min_angle_deg
                              << " deg");
    }
  }
}

BOOST_AUTO_TEST_CASE(fem_disc_area_matches_the_dda_geometry) {
  ImpactDisc impact;
  const Mesh mesh = generate_fem_mesh(impact, 0.004, FemCells::Triangles);
  BOOST_TEST(mesh.body_names == std::vector<std::string>{"disc"}, boost::test_tools::per_element());
  const double analytic = kPi * kRadius * kRadius - impact.connectivity * impact.diameter * impact.joint_width;
  BOOST_TEST(std::abs(body_area(mesh, "disc") - analytic) <= kAreaTolerance * analytic);
  BOOST_CHECK_THROW(generate_fem_mesh(impact, 0.0, FemCells::Triangles), MeshError);
}
