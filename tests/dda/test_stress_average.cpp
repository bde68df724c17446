// The fracture criterion's stress averaged over a radius (analysis.fracture_stress_radius): the
// neighbourhoods against their definition, and the mean of a linear stress field against the
// field at the joint, which it must approach as the blocks shrink (a radius fixed in metres is a
// material length: the mean it takes must not depend on the mesh).
#define BOOST_TEST_MODULE dda_stress_average
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "ddafrac/dda/block_system.hpp"
#include "ddafrac/dda/stress_average.hpp"
#include "support.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;

namespace {

constexpr double kSide = 0.1;     // m, the square plate
constexpr double kRadius = 0.01;  // m, the averaging radius

/// Largest shift of an interior node of plate(), as a fraction of the squares' side.
constexpr double kJitter = 0.25;

/// A square plate of n x n squares split into triangles, its interior nodes shifted by up to
/// kJitter of a square's side in a fixed pseudo-random pattern (a regular mesh's blocks lie
/// symmetrically about each joint, and their mean of a linear field is exact), one body with
/// virtual joints.
BlockSystem plate(int n) {
  meshes::Mesh m = testing::triangulated_bar(kSide, kSide, n, n);
  std::mt19937 random(20261206);
  const double shift = kJitter * kSide / n;
  for (meshes::Point& p : m.nodes) {
    const double dx = shift * (2.0 * random() / double(std::mt19937::max()) - 1.0);
    const double dy = shift * (2.0 * random() / double(std::mt19937::max()) - 1.0);
    if (p.x > 0.0 && p.x < kSide && p.y > 0.0 && p.y < kSide) {
      p.x += dx;
      p.y += dy;
    }
  }
  scene::Scene sc = testing::basic_scene(scene::Mode::Static, 1.0, 1e10, {0.0, 0.0});
  scene::JointSet rock;
  rock.name = "rock";
  rock.normal_stiffness = 1e10;
  rock.shear_stiffness = 4e9;
  sc.joint_sets.push_back(rock);
  scene::Body body = testing::body("rock");
  body.virtual_joints = 1;
  sc.bodies.push_back(body);
  return build_block_system(sc, m, true);
}

/// A linear stress field (σxx, σyy, τxy), Pa, with gradients of 20–30 MPa/m.
Vec3 linear_field(double x, double y) { return Vec3(1e6 + 2e7 * x, -5e5 + 3e7 * y, 1e7 * (x + y)); }
constexpr double kLargestGradient = 3e7;  // Pa/m, of any component of linear_field

/// Over the joints whose circle lies inside the plate: the largest |mean − σ(midpoint)| of any
/// component, Pa.
double largest_error_of_the_mean(int n) {
  BlockSystem s = plate(n);
  for (std::size_t b = 0; b < s.block_count(); ++b) s.stress[b] = linear_field(s.geometry[b].cx, s.geometry[b].cy);
  const StressNeighbourhoods hoods = stress_neighbourhoods(s, kRadius);
  double worst = 0.0;
  for (std::size_t j = 0; j < s.joints.size(); ++j) {
    const meshes::Point mid = s.joint_midpoint(s.joints[j]);
    if (std::min({mid.x, mid.y, kSide - mid.x, kSide - mid.y}) < 1.5 * kRadius) continue;
    const Vec3 error = neighbourhood_stress(s, hoods, j) - linear_field(mid.x, mid.y);
    worst = std::max(worst, error.cwiseAbs().maxCoeff());
  }
  return worst;
}

}  // namespace

// Each joint's neighbourhood is what its definition says: its two blocks and every block whose
// centroid lies within the radius of its midpoint, in increasing order, weighted by area with
// weights summing to 1 (to round-off).
BOOST_AUTO_TEST_CASE(a_neighbourhood_holds_the_blocks_within_the_radius_weighted_by_area) {
  const BlockSystem s = plate(12);
  for (const double radius : {1e-9, kRadius}) {
    const StressNeighbourhoods hoods = stress_neighbourhoods(s, radius);
    BOOST_REQUIRE_EQUAL(hoods.offsets.size(), s.joints.size() + 1);
    std::size_t largest = 0;
    for (std::size_t j = 0; j < s.joints.size(); ++j) {
      const Joint& jt = s.joints[j];
      const meshes::Point mid = s.joint_midpoint(jt);
      std::vector<Index> expected;
      double area = 0.0;
      for (std::size_t b = 0; b < s.block_count(); ++b)
        if (static_cast<Index>(b) == jt.block_a || static_cast<Index>(b) == jt.block_b ||
            std::hypot(s.geometry[b].cx - mid.x, s.geometry[b].cy - mid.y) <= radius) {
          expected.push_back(static_cast<Index>(b));
          area += s.geometry[b].area;
        }
      const std::vector<Index> got(hoods.blocks.begin() + hoods.offsets[j],
                                   hoods.blocks.begin() + hoods.offsets[j + 1]);
      BOOST_TEST(got == expected, boost::test_tools::per_element());
      double weights = 0.0;
      for (Index k = hoods.offsets[j]; k < hoods.offsets[j + 1]; ++k) {
        const auto b = static_cast<std::size_t>(hoods.blocks[static_cast<std::size_t>(k)]);
        BOOST_TEST(hoods.weights[static_cast<std::size_t>(k)] == s.geometry[b].area / area,
                   boost::test_tools::tolerance(1e-12));
        weights += hoods.weights[static_cast<std::size_t>(k)];
      }
      BOOST_TEST(weights == 1.0, boost::test_tools::tolerance(1e-12));
      largest = std::max(largest, got.size());
    }
    BOOST_TEST_MESSAGE("radius " << radius << " m: at most " << largest << " blocks per joint");
    if (radius == kRadius) BOOST_TEST(largest > 10u);
  }
}

// The area-weighted mean of a linear field over the blocks within the radius is the field at the
// weighted centroid of those blocks, which approaches the joint's midpoint as the blocks shrink:
// the error must fall with the mesh and end a small fraction of what the field changes across the
// radius (a mean over a fixed circle, not over the joint's two blocks, whose size sets it).
BOOST_AUTO_TEST_CASE(the_mean_of_a_linear_field_approaches_the_field_at_the_joint) {
  const double across = kLargestGradient * kRadius;  // Pa
  std::vector<double> errors;
  for (const int n : {20, 40, 80}) {
    errors.push_back(largest_error_of_the_mean(n) / across);
    BOOST_TEST_MESSAGE(n << " x " << n << " squares (h = " << kSide / n << " m): largest error of the mean "
                         << errors.back() << " of the change across the radius");
  }
  BOOST_TEST(errors[1] < errors[0]);
  BOOST_TEST(errors[2] < errors[1]);
  BOOST_TEST(errors[2] <= 0.05);
}
