// Geometry of the generated DDA meshes: areas, slot length and angle, orientation, group names,
// rigid bodies, determinism, and measure_quality on a hand-made mesh.
#define BOOST_TEST_MODULE meshes_geometry
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "ddafrac/meshes/generate.hpp"
#include "mesh_checks.hpp"

using namespace ddafrac::meshes;
using namespace ddafrac::meshes::testing;

namespace {

constexpr int kBlocks = 3000;            // coarse enough to be quick, fine enough for 0.1%
constexpr double kAreaTolerance = 1e-3;  // relative; the polygonal rim loses ~ (h/R)^2/6
constexpr double kDiameter = 0.1;        // m
constexpr double kRadius = kDiameter / 2;
constexpr double kExact = 1e-12;  // m, for points the geometry puts on exact places

Mesh dda(const Geometry& geometry, QualityReport* report = nullptr) {
  MeshControl control;
  control.target_blocks = kBlocks;
  return generate_dda_mesh(geometry, control, report);
}

void check_area(const Geometry& geometry, double analytic_area) {
  const Mesh mesh = dda(geometry);
  const double area = body_area(mesh, "disc");
  BOOST_TEST_MESSAGE("disc area " << area << " m^2, analytic " << analytic_area << " m^2");
  BOOST_TEST(std::abs(area - analytic_area) <= kAreaTolerance * analytic_area);
}

/// Principal axis of the slot group's nodes (the faces are symmetric about it) and the extent
/// of the nodes along it.
SlotMeasure principal_slot(const Mesh& mesh, const std::string& group) {
  const std::vector<Point> points = group_nodes(mesh, group);
  double sxx = 0, syy = 0, sxy = 0;
  for (const Point& p : points) {
    sxx += p.x * p.x;
    syy += p.y * p.y;
    sxy += p.x * p.y;
  }
  const double angle = std::fmod(0.5 * std::atan2(2 * sxy, sxx - syy) + 2 * kPi, kPi);
  double lo = HUGE_VAL, hi = -HUGE_VAL;
  for (const Point& p : points) {
    const double along = p.x * std::cos(angle) + p.y * std::sin(angle);
    lo = std::min(lo, along);
    hi = std::max(hi, along);
  }
  return {hi - lo, angle};
}

void check_slot(const Geometry& geometry, const std::string& group, double length, double inclination) {
  QualityReport report;
  const Mesh mesh = dda(geometry, &report);
  const SlotMeasure slot = principal_slot(mesh, group);
  const double h = report.element_size;
  BOOST_TEST_MESSAGE(group << ": length " << slot.length << " m (spec " << length << "), angle " << slot.angle / kDegree
                           << " deg (spec " << inclination / kDegree << ")");
  BOOST_TEST(std::abs(slot.length - length) <= h);
  // An end of the slot displaced by one element size turns it by at most h / (L/2).
  const double angle_error = std::abs(std::remainder(slot.angle - inclination, kPi));
  BOOST_TEST(angle_error <= h / (length / 2));
}

bool has_node_at(const Mesh& mesh, double x, double y) {
  for (const Point& p : mesh.nodes) {
    if (std::abs(p.x - x) <= kExact && std::abs(p.y - y) <= kExact) return true;
  }
  return false;
}

/// The one cell of a rigid body: four nodes, spanning [x0, x1] x [y0, y1].
void check_rectangle(const Mesh& mesh, const std::string& body, double x0, double y0, double x1, double y1) {
  BOOST_TEST_CONTEXT(body) {
    BOOST_REQUIRE_EQUAL(body_cells(mesh, body), 1u);
    const long b = index_of(mesh.body_names, body);
    for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
      if (static_cast<long>(mesh.cell_body[c]) != b) continue;
      BOOST_TEST(mesh.cell_size(c) == 4u);
      BOOST_TEST(std::abs(cell_area(mesh, c) - (x1 - x0) * (y1 - y0)) <= kExact);
      for (std::size_t k = 0; k < 4; ++k) {
        const Point& p = mesh.nodes[mesh.cell_begin(c)[k]];
        BOOST_TEST((std::abs(p.x - x0) <= kExact || std::abs(p.x - x1) <= kExact));
        BOOST_TEST((std::abs(p.y - y0) <= kExact || std::abs(p.y - y1) <= kExact));
      }
    }
  }
}

}  // namespace

// Analytic areas: disc pi R^2; flats of central angle phi remove 2 * R^2/2 (phi - sin phi);
// a slot removes length * width.
BOOST_AUTO_TEST_CASE(meshed_area_equals_analytic_area) {
  check_area(PlainDisc{}, kPi * kRadius * kRadius);
  FlattenedDisc flattened;
  flattened.with_platens = false;
  const double phi = flattened.flat_angle;
  check_area(flattened, kPi * kRadius * kRadius - kRadius * kRadius * (phi - std::sin(phi)));
  SlitDisc slit;
  check_area(slit, kPi * kRadius * kRadius - slit.slit.length * slit.slit.width);
  ImpactDisc impact;
  impact.connectivity = 0.75;
  check_area(impact, kPi * kRadius * kRadius - impact.connectivity * kDiameter * impact.joint_width);
}

BOOST_AUTO_TEST_CASE(slit_and_joint_length_and_angle_match_the_spec) {
  for (double inclination : {30.0, 75.0}) {
    SlitDisc disc;
    disc.slit.inclination = inclination * kDegree;
    check_slot(disc, "slit", disc.slit.length, disc.slit.inclination);
  }
  for (double theta : {0.0, 45.0, 90.0}) {
    ImpactDisc disc;
    disc.connectivity = 0.5;
    disc.joint_angle = theta * kDegree;
    check_slot(disc, "joint", disc.connectivity * disc.diameter, disc.joint_angle);
  }
}

BOOST_AUTO_TEST_CASE(cells_counter_clockwise_and_boundary_edges_follow_their_cells) {
  PlainDisc loaded;
  loaded.load_half_angle = 0.1;
  FlattenedDisc precracked;
  precracked.slit = Slit{};
  for (const Geometry& geometry :
       std::vector<Geometry>{loaded, FlattenedDisc{}, precracked, SlitDisc{}, ImpactDisc{}}) {
    const Mesh mesh = dda(geometry);
    BOOST_TEST(smallest_relative_area(mesh) > 0.0);
    BOOST_TEST(misoriented_boundary_edges(mesh) == 0u);
    BOOST_TEST(!mesh.boundary_edges.empty());
  }
}

BOOST_AUTO_TEST_CASE(physical_group_names) {
  using Names = std::vector<std::string>;
  auto sorted = [](Names names) {
    std::sort(names.begin(), names.end());
    return names;
  };
  PlainDisc loaded;
  loaded.load_half_angle = 0.1;
  const Mesh plain = dda(loaded);
  BOOST_TEST(plain.body_names == Names{"disc"}, boost::test_tools::per_element());
  BOOST_TEST(sorted(plain.boundary_names) == (Names{"load_bottom", "load_top", "rim"}),
             boost::test_tools::per_element());

  FlattenedDisc precracked;
  precracked.slit = Slit{};
  const Mesh flattened = dda(precracked);
  BOOST_TEST(flattened.body_names == (Names{"disc", "top_platen", "bottom_platen"}), boost::test_tools::per_element());
  BOOST_TEST(sorted(flattened.boundary_names) == (Names{"flat_bottom", "flat_top", "rim", "slit"}),
             boost::test_tools::per_element());

  const Mesh slit = dda(SlitDisc{});
  BOOST_TEST(slit.body_names == Names{"disc"}, boost::test_tools::per_element());
  BOOST_TEST(sorted(slit.boundary_names) == (Names{"rim", "slit"}), boost::test_tools::per_element());

  const Mesh impact = dda(ImpactDisc{});
  BOOST_TEST(impact.body_names == (Names{"disc", "plate"}), boost::test_tools::per_element());
  BOOST_TEST(sorted(impact.boundary_names) == (Names{"impact_patch", "joint", "rim"}),
             boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(loaded_arcs_and_impact_patch_have_the_requested_half_angle) {
  constexpr double kAngleTolerance = 1e-9;  // rad; the arc ends are geometry points
  PlainDisc loaded;
  loaded.load_half_angle = 0.1;
  const Mesh plain = dda(loaded);
  BOOST_TEST(std::abs(half_angle_about(plain, "load_top", kPi / 2) - 0.1) <= kAngleTolerance);
  BOOST_TEST(std::abs(half_angle_about(plain, "load_bottom", -kPi / 2) - 0.1) <= kAngleTolerance);

  ImpactDisc impact;
  const Mesh mesh = dda(impact);
  BOOST_TEST(std::abs(half_angle_about(mesh, "impact_patch", -kPi / 2) - impact.patch_half_angle) <= kAngleTolerance);
}

BOOST_AUTO_TEST_CASE(impact_plate_touches_the_lowest_disc_point_which_is_a_node) {
  ImpactDisc impact;
  const Mesh mesh = dda(impact);
  BOOST_TEST(has_node_at(mesh, 0.0, -kRadius));
  check_rectangle(mesh, "plate", -impact.plate_width / 2, -kRadius - impact.plate_height, impact.plate_width / 2,
                  -kRadius);
}

BOOST_AUTO_TEST_CASE(platens_touch_the_flats) {
  FlattenedDisc disc;
  const Mesh mesh = dda(disc);
  const double flat_y = kRadius * std::cos(disc.flat_angle / 2);
  check_rectangle(mesh, "top_platen", -disc.platen_width / 2, flat_y, disc.platen_width / 2,
                  flat_y + disc.platen_thickness);
  check_rectangle(mesh, "bottom_platen", -disc.platen_width / 2, -flat_y - disc.platen_thickness, disc.platen_width / 2,
                  -flat_y);
  for (const Point& p : group_nodes(mesh, "flat_top")) BOOST_TEST(std::abs(p.y - flat_y) <= kExact);
  for (const Point& p : group_nodes(mesh, "flat_bottom")) {
    BOOST_TEST(std::abs(p.y + flat_y) <= kExact);
  }

  disc.with_platens = false;
  BOOST_TEST(dda(disc).body_names == std::vector<std::string>{"disc"}, boost::test_tools::per_element());
}

BOOST_AUTO_TEST_CASE(same_input_gives_an_identical_mesh) {
  ImpactDisc impact;
  impact.joint_angle = 30.0 * kDegree;
  const Mesh first = dda(impact);
  const Mesh second = dda(impact);
  BOOST_TEST(same_mesh(first, second, 0.0));
}

BOOST_AUTO_TEST_CASE(measure_quality_of_a_hand_made_mesh) {
  // An equilateral triangle (min angle 60 deg) and a right isosceles one (45 deg), clockwise
  // node order in neither.
  Mesh mesh;
  mesh.nodes = {{0, 0}, {1, 0}, {0.5, std::sqrt(3.0) / 2}, {2, 0}, {2, 1}};
  mesh.cell_nodes = {0, 1, 2, 1, 3, 4};
  mesh.cell_offsets = {0, 3, 6};
  mesh.cell_body = {0, 0};
  mesh.body_names = {"disc"};
  const QualityReport report = measure_quality(mesh, "disc");
  BOOST_TEST(report.blocks == 2u);
  BOOST_TEST(report.min_angle_deg == 45.0, boost::test_tools::tolerance(1e-9));
  BOOST_TEST(report.mean_min_angle_deg == 52.5, boost::test_tools::tolerance(1e-9));
  BOOST_CHECK_THROW(measure_quality(mesh, "plate"), MeshError);
}

BOOST_AUTO_TEST_CASE(invalid_geometry_is_a_mesh_error) {
  SlitDisc too_long;
  too_long.slit.length = kDiameter;
  BOOST_CHECK_THROW(dda(too_long), MeshError);
  ImpactDisc no_joint;
  no_joint.connectivity = 0.0;
  BOOST_CHECK_THROW(dda(no_joint), MeshError);
  MeshControl bad;
  bad.target_blocks = 0;
  BOOST_CHECK_THROW(generate_dda_mesh(PlainDisc{}, bad), MeshError);
}

namespace {
/// Shortest cell edge of the disc (m): where the mesh is finest, at the slot ends.
double shortest_disc_edge(const Mesh& mesh) {
  const long disc = index_of(mesh.body_names, "disc");
  double shortest = HUGE_VAL;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (static_cast<long>(mesh.cell_body[c]) != disc) continue;
    const std::size_t n = mesh.cell_size(c);
    for (std::size_t k = 0; k < n; ++k) {
      const Point& p = mesh.nodes[mesh.cell_begin(c)[k]];
      const Point& q = mesh.nodes[mesh.cell_begin(c)[(k + 1) % n]];
      shortest = std::min(shortest, std::hypot(q.x - p.x, q.y - p.y));
    }
  }
  return shortest;
}
}  // namespace

// mesh.slot_end_size: the tips are meshed at the given multiple of the slot width. At the default
// (one width) the 0.4 mm end face is one or two edges; at a quarter width it takes about four, so
// the shortest edge must fall by at least half, and no edge may be shorter than half the
// requested size (gmsh meets a size field within a factor of about 1.5).
BOOST_AUTO_TEST_CASE(slot_end_size_refines_the_slot_ends) {
  const ImpactDisc impact;
  MeshControl control;
  control.target_blocks = kBlocks;
  const double at_default = shortest_disc_edge(generate_dda_mesh(impact, control));
  control.slot_end_size_per_width = 0.25;
  const double at_quarter = shortest_disc_edge(generate_dda_mesh(impact, control));
  BOOST_TEST_MESSAGE("shortest disc edge: " << at_default * 1e3 << " mm at 1 slot width, " << at_quarter * 1e3
                                            << " mm at 0.25 (slot width " << impact.joint_width * 1e3 << " mm)");
  BOOST_TEST(at_quarter <= 0.5 * at_default);
  BOOST_TEST(at_quarter >= 0.5 * 0.25 * impact.joint_width);
}
