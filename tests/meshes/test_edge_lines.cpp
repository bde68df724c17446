// Straight lines of block edges: exact lengths on hand-made grids, and the two gmsh algorithms
// of the DDA mesh compared on the study's 2045-block flattened disc.
#define BOOST_TEST_MODULE meshes_edge_lines
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <cstdlib>

#include "ddafrac/meshes/edge_lines.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "mesh_checks.hpp"

using namespace ddafrac::meshes;

namespace {

constexpr double kExact = 1e-12;  // m: sums of a few unit lengths

/// A grid of nx x ny unit squares, each cut into two triangles by a diagonal: all the same way
/// (a line of diagonals crosses the grid), or alternating from column to column (a herringbone
/// whose diagonals turn by 90 degrees at every node).
Mesh grid(int nx, int ny, bool alternate_diagonals) {
  Mesh mesh;
  auto node = [nx](int i, int j) { return static_cast<Index>(j * (nx + 1) + i); };
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) mesh.nodes.push_back({double(i), double(j)});
  }
  auto add = [&mesh](Index a, Index b, Index c) {
    mesh.cell_nodes.insert(mesh.cell_nodes.end(), {a, b, c});
    mesh.cell_offsets.push_back(static_cast<Index>(mesh.cell_nodes.size()));
    mesh.cell_body.push_back(0);
  };
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const Index p = node(i, j), q = node(i + 1, j), r = node(i + 1, j + 1), s = node(i, j + 1);
      if (alternate_diagonals && i % 2 == 1) {
        add(p, q, s);
        add(q, r, s);
      } else {
        add(p, q, r);
        add(p, r, s);
      }
    }
  }
  mesh.body_names = {"disc"};
  return mesh;
}

Mesh flattened_disc(MeshAlgorithm algorithm, QualityReport* report) {
  MeshControl control;
  control.target_blocks = 2045;  // the study's coarsest flattened disc
  control.algorithm = algorithm;
  return generate_dda_mesh(FlattenedDisc{}, control, report);
}

}  // namespace

// Boundary edges (one cell) are no part of a line: on a 4 x 3 grid the longest interior line is
// the diagonal from (0,0) to (3,3); the rows and columns inside are 4 and 3 long.
BOOST_AUTO_TEST_CASE(the_diagonal_of_a_regular_grid_is_its_longest_line) {
  BOOST_TEST(std::abs(longest_straight_edge_line(grid(4, 3, false)) - 3.0 * std::sqrt(2.0)) <= kExact);
}

BOOST_AUTO_TEST_CASE(a_herringbone_grid_has_only_its_rows_and_columns) {
  BOOST_TEST(std::abs(longest_straight_edge_line(grid(4, 3, true)) - 4.0) <= kExact);
}

// Moving the middle node of a 2 x 2 grid by 0.1 along x turns the diagonal through it by 5.7
// degrees: under the default 5 that breaks it, and the longest line is the middle row (2, which
// the move does not turn); under 10 the diagonal holds.
BOOST_AUTO_TEST_CASE(the_turn_limit_decides_where_a_line_ends) {
  Mesh mesh = grid(2, 2, false);
  mesh.nodes[4].x += 0.1;
  const double diagonal = std::hypot(1.1, 1.0) + std::hypot(0.9, 1.0);
  BOOST_TEST(std::abs(longest_straight_edge_line(mesh, "disc", 10.0) - diagonal) <= kExact);
  BOOST_TEST(std::abs(longest_straight_edge_line(mesh) - 2.0) <= kExact);
  BOOST_CHECK_THROW(longest_straight_edge_line(mesh, "plate"), MeshError);
}

// The Delaunay mesh is a different mesh of the same disc (block count, area), and its edges line
// up into much shorter straight lines than Frontal-Delaunay's rows.
BOOST_AUTO_TEST_CASE(delaunay_lines_up_fewer_edges_than_frontal_delaunay) {
  QualityReport frontal_report, delaunay_report;
  const Mesh frontal = flattened_disc(MeshAlgorithm::FrontalDelaunay, &frontal_report);
  const Mesh delaunay = flattened_disc(MeshAlgorithm::Delaunay, &delaunay_report);
  const double frontal_line = longest_straight_edge_line(frontal);
  const double delaunay_line = longest_straight_edge_line(delaunay);
  BOOST_TEST_MESSAGE("frontal-delaunay: " << frontal_report.blocks << " blocks, mean min angle "
                                          << frontal_report.mean_min_angle_deg << " deg, longest line "
                                          << frontal_line * 1e3 << " mm; delaunay: " << delaunay_report.blocks
                                          << " blocks, mean min angle " << delaunay_report.mean_min_angle_deg
                                          << " deg, longest line " << delaunay_line * 1e3 << " mm");
  BOOST_TEST(std::abs(static_cast<double>(delaunay_report.blocks) - 2045.0) <= MeshControl{}.block_tolerance * 2045.0);
  BOOST_TEST(std::abs(testing::body_area(delaunay, "disc") - testing::body_area(frontal, "disc")) <=
             1e-3 * testing::body_area(frontal, "disc"));
  BOOST_TEST(!testing::same_mesh(frontal, delaunay, 0.0));
  // Measured: 93 mm against 16 mm. Frontal-Delaunay's rows give a line across most of the
  // 100 mm disc; Delaunay's must not give even half of that.
  BOOST_TEST(frontal_line > 0.5 * FlattenedDisc{}.diameter);
  BOOST_TEST(delaunay_line < 0.5 * frontal_line);
}
