// The DDA twin of the continuum (coupling/verify, dda_twin.hpp): the one place that sets a
// twin's joint stiffnesses, for the static and the dynamic comparison alike.
#define BOOST_TEST_MODULE coupling_dda_twin
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "ddafrac/coupling/dda_twin.hpp"
#include "ddafrac/scene/parse.hpp"

using namespace ddafrac;

namespace {

scene::Scene impact_scene() {
  return scene::load_scene(std::filesystem::path(DDAFRAC_SOURCE_DIR) / "scenes" / "verify" / "impact_elastic.toml");
}

double disc_young(const scene::Scene& s) { return s.materials.at(coupling::disc_body(s).material).young; }

}  // namespace

BOOST_AUTO_TEST_CASE(every_joint_set_gets_kn_from_the_ratio_and_keeps_its_own_shear_ratio) {
  scene::Scene s = impact_scene();
  BOOST_REQUIRE(s.joint_sets.size() >= 2u);
  s.joint_sets[0].shear_stiffness = 0.25 * s.joint_sets[0].normal_stiffness;  // a set with its own ks/kn
  const double young = disc_young(s);
  const coupling::DdaTwin twin = coupling::bonded_dda_twin(s, 10.0);
  for (std::size_t k = 0; k < s.joint_sets.size(); ++k) {
    const auto& before = s.joint_sets[k];
    const auto& after = twin.scene.joint_sets[k];
    BOOST_TEST(after.normal_stiffness == 10.0 * young);
    BOOST_TEST(after.shear_stiffness / after.normal_stiffness == before.shear_stiffness / before.normal_stiffness,
               boost::test_tools::tolerance(1e-15));
  }
  BOOST_TEST(twin.kn == 10.0 * young);
  BOOST_TEST(twin.scene.analysis.penalty == twin.kn);
}

BOOST_AUTO_TEST_CASE(only_the_virtual_joints_become_unbreakable_and_gravity_is_off) {
  scene::Scene s = impact_scene();
  s.analysis.gravity = {0.0, -9.81};
  const std::size_t virtual_set = *coupling::disc_body(s).virtual_joints;
  BOOST_REQUIRE(s.real_joints != virtual_set);
  const coupling::DdaTwin twin = coupling::bonded_dda_twin(s, 100.0);
  BOOST_TEST(std::isinf(twin.scene.joint_sets.at(virtual_set).tensile_strength));
  BOOST_TEST(std::isinf(twin.scene.joint_sets.at(virtual_set).cohesion));
  BOOST_TEST(twin.scene.joint_sets.at(s.real_joints).tensile_strength ==
             s.joint_sets.at(s.real_joints).tensile_strength);
  BOOST_TEST(twin.scene.analysis.gravity[1] == 0.0);
}

BOOST_AUTO_TEST_CASE(a_ratio_of_zero_keeps_the_scene_stiffnesses) {
  const scene::Scene s = impact_scene();
  const coupling::DdaTwin twin = coupling::bonded_dda_twin(s, 0.0);
  for (std::size_t k = 0; k < s.joint_sets.size(); ++k) {
    BOOST_TEST(twin.scene.joint_sets[k].normal_stiffness == s.joint_sets[k].normal_stiffness);
    BOOST_TEST(twin.scene.joint_sets[k].shear_stiffness == s.joint_sets[k].shear_stiffness);
  }
  BOOST_TEST(twin.kn == s.joint_sets.at(*coupling::disc_body(s).virtual_joints).normal_stiffness);
}

BOOST_AUTO_TEST_CASE(a_disc_without_virtual_joints_has_no_twin) {
  scene::Scene s = impact_scene();
  for (auto& b : s.bodies)
    if (b.role == scene::Role::Disc) b.virtual_joints.reset();
  BOOST_CHECK_THROW(coupling::bonded_dda_twin(s, 100.0), std::runtime_error);
}
