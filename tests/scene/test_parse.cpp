// Scene parsing: a valid scene gives the values it states (in SI units), and each of many
// bad scenes is refused with a message that names the file, line, key and what was expected.
#define BOOST_TEST_MODULE scene_parse
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/scene/parse.hpp"
#include "ddafrac/scene/sweep.hpp"

using namespace ddafrac;

namespace {

using common::kPi;

// A complete, valid scene; each bad case below changes one thing in it. Line numbers in the
// expectations refer to this text (line 1 is `name = ...`).
const std::string kValid = R"(name = "t"
[analysis]
mode = "dynamic"
plane = "stress"
dt_max = 1e-7
max_displacement_ratio = 1e-4
penalty = 0.35e9
end_time = 1.8e-3
output_interval = 2e-5
gravity = [0.0, -9.81]
[materials.rock]
density = 2050
young = 10.53e9
poisson = 0.12
[joints.virtual]
friction_angle = 38.5
cohesion = 8.29e6
tensile_strength = 7.86e6
[joints.real]
friction_angle = 20
cohesion = 1e6
tensile_strength = 10
[contacts]
real_joints = "real"
[geometry]
generator = "impact_disc"
diameter = 0.1
joint_angle = 45
connectivity = 0.25
joint_width = 0.4e-3
plate_width = 0.1
plate_height = 0.02
[mesh]
blocks = 1200
[bodies.disc]
material = "rock"
role = "disc"
motion = "free"
virtual_joints = "virtual"
velocity = [0.0, -3.5]
[bodies.plate]
material = "rock"
role = "plate"
motion = "fixed"
[[gauges]]
name = "A"
position = [0.0, -0.045]
)";

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  BOOST_REQUIRE_MESSAGE(at != std::string::npos, "test setup: '" << from << "' not in the valid scene");
  return text.replace(at, from.size(), to);
}

/// Parses `text` and returns the problems it was refused for (fails if it was accepted).
std::vector<scene::Problem> problems_of(const std::string& text) {
  try {
    scene::parse_scene(text, "bad.toml");
  } catch (const scene::SceneError& e) {
    return e.problems();
  }
  BOOST_FAIL("the scene was accepted");
  return {};
}

/// Exactly one problem, at `key` (and `line` if > 0), whose message contains `fragment`.
void expect_problem(const std::string& text, const std::string& key, int line, const std::string& fragment) {
  const auto problems = problems_of(text);
  BOOST_TEST_REQUIRE(problems.size() == 1u);
  const scene::Problem& p = problems.front();
  BOOST_TEST_INFO("message: " << p.to_string());
  BOOST_TEST(p.file == "bad.toml");
  BOOST_TEST(p.key == key);
  if (line > 0) BOOST_TEST(p.line == line);
  BOOST_TEST(p.message.find(fragment) != std::string::npos);
}

}  // namespace

BOOST_AUTO_TEST_CASE(valid_scene_gives_stated_values_in_si_units) {
  const scene::Scene s = scene::parse_scene(kValid, "ok.toml");
  BOOST_TEST(s.name == "t");
  BOOST_TEST(s.analysis.dt_max == 1e-7);
  BOOST_TEST(s.analysis.penalty == 0.35e9);
  BOOST_TEST(s.analysis.gravity[1] == -9.81);
  BOOST_TEST(s.materials.size() == 1u);
  BOOST_TEST(s.materials[0].young == 10.53e9);
  BOOST_TEST_REQUIRE(s.joint_sets.size() == 2u);
  BOOST_TEST(s.joint_sets[0].name == "virtual");
  BOOST_TEST(std::abs(s.joint_sets[0].friction_angle - 38.5 * kPi / 180) < 1e-15);
  // Stiffnesses default to the analysis penalty and ks = 0.4 kn when the joint set gives none.
  BOOST_TEST(s.joint_sets[0].normal_stiffness == 0.35e9);
  BOOST_TEST(s.joint_sets[0].shear_stiffness == 0.4 * 0.35e9);
  // The contact search: search distance 2.5 × the allowed step displacement, pair-list skin 1 ×
  // the search distance.
  BOOST_TEST(s.analysis.search_distance_factor == 2.5);
  BOOST_TEST(s.analysis.pair_list_skin_factor == 1.0);
  BOOST_TEST(s.real_joints == 1u);
  const auto& g = std::get<meshes::ImpactDisc>(s.geometry);
  BOOST_TEST(std::abs(g.joint_angle - kPi / 4) < 1e-15);
  BOOST_TEST(g.connectivity == 0.25);
  BOOST_TEST(s.mesh.target_blocks == 1200);
  BOOST_TEST_REQUIRE(s.bodies.size() == 2u);
  BOOST_TEST(s.bodies[0].name == "disc");
  BOOST_TEST(s.bodies[0].virtual_joints.value() == 0u);
  BOOST_TEST(s.bodies[0].initial_velocity[1] == -3.5);
  BOOST_TEST((s.bodies[1].motion == scene::Motion::Fixed));
  BOOST_TEST_REQUIRE(s.gauges.size() == 1u);
  BOOST_TEST(s.gauges[0].position[1] == -0.045);
}

// A study runs a scene that repeats another under a new name once (the source study's cases 8
// and 12 are case 4): scenes that differ only in name and description have one unnamed_text, and
// a changed value, here a gauge's name, makes it differ.
BOOST_AUTO_TEST_CASE(unnamed_text_tells_a_renamed_scene_from_a_changed_one) {
  const scene::Scene original = scene::parse_scene(kValid, "ok.toml");
  const scene::Scene renamed =
      scene::parse_scene(replaced(kValid, "name = \"t\"", "name = \"u\"\ndescription = \"the same run\""), "u.toml");
  const scene::Scene changed = scene::parse_scene(replaced(kValid, "name = \"A\"", "name = \"B\""), "ok.toml");
  BOOST_TEST(renamed.name == "u");
  BOOST_TEST(renamed.resolved_text != original.resolved_text);
  BOOST_TEST(renamed.unnamed_text == original.unnamed_text);
  BOOST_TEST(changed.unnamed_text != original.unnamed_text);
  BOOST_TEST(original.unnamed_text.find("[analysis]") != std::string::npos);
}

// --- at least twenty bad scenes, each with its message -----------------------------------

BOOST_AUTO_TEST_CASE(unknown_key_suggests_the_closest) {
  expect_problem(replaced(kValid, "dt_max = 1e-7", "dt_max = 1e-7\ndt_mx = 2"), "analysis.dt_mx", 6,
                 "did you mean \"dt_max\"");
}

BOOST_AUTO_TEST_CASE(unknown_table_suggests_the_closest) {
  expect_problem(kValid + "[outptu]\nvtk = true\n", "outptu", 0, "did you mean \"output\"");
}

BOOST_AUTO_TEST_CASE(wrong_type_names_expected_and_found) {
  expect_problem(replaced(kValid, "dt_max = 1e-7", "dt_max = \"small\""), "analysis.dt_max", 5,
                 "expected a number > 0 (s), got a string");
}

BOOST_AUTO_TEST_CASE(missing_required_value) {
  expect_problem(replaced(kValid, "end_time = 1.8e-3\n", ""), "analysis.end_time", 2, "missing required value");
}

BOOST_AUTO_TEST_CASE(missing_required_table) {
  expect_problem(replaced(kValid, "[contacts]\nreal_joints = \"real\"\n", ""), "contacts", 0,
                 "missing required table [contacts]");
}

BOOST_AUTO_TEST_CASE(poisson_ratio_of_one_half_is_refused) {
  expect_problem(replaced(kValid, "poisson = 0.12", "poisson = 0.5"), "materials.rock.poisson", 14, "in [0, 0.5)");
}

BOOST_AUTO_TEST_CASE(negative_density_is_refused) {
  expect_problem(replaced(kValid, "density = 2050", "density = -2050"), "materials.rock.density", 12,
                 "> 0 (kg/m^3), got -2050");
}

BOOST_AUTO_TEST_CASE(zero_time_step_is_refused) {
  expect_problem(replaced(kValid, "dt_max = 1e-7", "dt_max = 0"), "analysis.dt_max", 5, "> 0 (s), got 0");
}

BOOST_AUTO_TEST_CASE(contact_search_factors_are_read_when_given) {
  const scene::Scene s =
      scene::parse_scene(replaced(kValid, "gravity = [0.0, -9.81]",
                                  "gravity = [0.0, -9.81]\nsearch_distance_factor = 0.25\npair_list_skin_factor = 0"),
                         "ok.toml");
  BOOST_TEST(s.analysis.search_distance_factor == 0.25);
  BOOST_TEST(s.analysis.pair_list_skin_factor == 0.0);
}

BOOST_AUTO_TEST_CASE(solver_tolerance_defaults_to_the_documented_value_and_is_read_when_given) {
  BOOST_TEST(scene::parse_scene(kValid, "ok.toml").analysis.solver_tolerance == scene::kDefaultSolverTolerance);
  const scene::Scene s = scene::parse_scene(
      replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nsolver_tolerance = 1e-13"), "ok.toml");
  BOOST_TEST(s.analysis.solver_tolerance == 1e-13);
}

BOOST_AUTO_TEST_CASE(a_solver_tolerance_round_off_cannot_reach_is_refused) {
  expect_problem(replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nsolver_tolerance = 1e-16"),
                 "analysis.solver_tolerance", 11, "got 1e-16");
}

BOOST_AUTO_TEST_CASE(node_ties_and_the_stress_criterion_are_off_unless_given) {
  const scene::Scene plain = scene::parse_scene(kValid, "ok.toml");
  BOOST_TEST((plain.analysis.intact_nodes == scene::IntactNodes::Contact));
  BOOST_TEST((plain.analysis.fracture_load == scene::FractureLoad::JointSprings));
  const scene::Scene s =
      scene::parse_scene(replaced(kValid, "gravity = [0.0, -9.81]",
                                  "gravity = [0.0, -9.81]\nintact_nodes = \"tie\"\nfracture_load = \"block_stress\""),
                         "ok.toml");
  BOOST_TEST((s.analysis.intact_nodes == scene::IntactNodes::Tie));
  BOOST_TEST((s.analysis.fracture_load == scene::FractureLoad::BlockStress));
}

BOOST_AUTO_TEST_CASE(an_unknown_node_rule_or_fracture_load_is_refused_with_the_choices) {
  expect_problem(replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nintact_nodes = \"glue\""),
                 "analysis.intact_nodes", 11, "tie");
  expect_problem(replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nfracture_load = \"stress\""),
                 "analysis.fracture_load", 11, "block_stress");
}

BOOST_AUTO_TEST_CASE(a_stress_radius_needs_the_stress_criterion_and_no_sign) {
  BOOST_TEST(scene::parse_scene(kValid, "ok.toml").analysis.fracture_stress_radius == 0.0);
  const scene::Scene s = scene::parse_scene(
      replaced(kValid, "gravity = [0.0, -9.81]",
               "gravity = [0.0, -9.81]\nfracture_load = \"block_stress\"\nfracture_stress_radius = 0.003"),
      "ok.toml");
  BOOST_TEST(s.analysis.fracture_stress_radius == 0.003);
  expect_problem(replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nfracture_stress_radius = 0.003"),
                 "analysis.fracture_stress_radius", 11, "needs analysis.fracture_load = \"block_stress\"");
  expect_problem(replaced(kValid, "gravity = [0.0, -9.81]",
                          "gravity = [0.0, -9.81]\nfracture_load = \"block_stress\"\nfracture_stress_radius = -1"),
                 "analysis.fracture_stress_radius", 12, "got -1");
}

BOOST_AUTO_TEST_CASE(a_fracture_energy_softens_virtual_joints_judged_on_their_springs) {
  BOOST_TEST(scene::parse_scene(kValid, "ok.toml").joint_sets[0].fracture_energy == 0.0);
  const std::string softening =
      replaced(kValid, "tensile_strength = 7.86e6", "tensile_strength = 7.86e6\nfracture_energy = 80");
  BOOST_TEST(scene::parse_scene(softening, "ok.toml").joint_sets[0].fracture_energy == 80.0);
  expect_problem(replaced(kValid, "tensile_strength = 7.86e6", "tensile_strength = 7.86e6\nfracture_energy = -1"),
                 "joints.virtual.fracture_energy", 19, "got -1");
  expect_problem(
      replaced(softening, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nfracture_load = \"block_stress\""),
      "joints.virtual.fracture_energy", 20, "analysis.fracture_load = \"joint_springs\"");
  expect_problem(replaced(softening, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nintact_nodes = \"tie\""),
                 "joints.virtual.fracture_energy", 20, "analysis.intact_nodes = \"contact\"");
  expect_problem(replaced(kValid, "tensile_strength = 10", "tensile_strength = 10\nfracture_energy = 80"),
                 "contacts.real_joints", 25, "only virtual joints");
}

// How a softening joint combines its modes: by default each on its own (none); "quadratic"
// combines them, and only for a softening set; any other name is refused with the choices.
BOOST_AUTO_TEST_CASE(a_softening_joint_set_chooses_how_its_modes_combine) {
  BOOST_TEST(static_cast<int>(scene::parse_scene(kValid, "ok.toml").joint_sets[0].mode_interaction) ==
             static_cast<int>(scene::ModeInteraction::None));
  const std::string mixed =
      replaced(kValid, "tensile_strength = 7.86e6",
               "tensile_strength = 7.86e6\nfracture_energy = 80\nmode_interaction = \"quadratic\"");
  BOOST_TEST(static_cast<int>(scene::parse_scene(mixed, "ok.toml").joint_sets[0].mode_interaction) ==
             static_cast<int>(scene::ModeInteraction::Quadratic));
  expect_problem(
      replaced(kValid, "tensile_strength = 7.86e6", "tensile_strength = 7.86e6\nmode_interaction = \"quadratic\""),
      "joints.virtual.mode_interaction", 19, "needs fracture_energy or shear_fracture_energy");
  expect_problem(replaced(mixed, "\"quadratic\"", "\"linear\""), "joints.virtual.mode_interaction", 20, "quadratic");
}

// A fracture energy of its own for shear (mode II): absent, shear softens with the tension's law;
// given alone, the joints soften in shear and stay brittle in tension, with the same conditions.
BOOST_AUTO_TEST_CASE(a_shear_fracture_energy_softens_shear_on_its_own_law) {
  const scene::JointSet brittle = scene::parse_scene(kValid, "ok.toml").joint_sets[0];
  BOOST_TEST(!brittle.shear_fracture_energy.has_value());
  BOOST_TEST(!brittle.softens());
  const std::string shear =
      replaced(kValid, "tensile_strength = 7.86e6", "tensile_strength = 7.86e6\nshear_fracture_energy = 800");
  const scene::JointSet js = scene::parse_scene(shear, "ok.toml").joint_sets[0];
  BOOST_TEST(js.shear_fracture_energy.value_or(-1.0) == 800.0);
  BOOST_TEST(js.fracture_energy == 0.0);
  BOOST_TEST(js.softens());
  const std::string brittle_shear =
      replaced(kValid, "tensile_strength = 7.86e6", "tensile_strength = 7.86e6\nshear_fracture_energy = 0");
  BOOST_TEST(scene::parse_scene(brittle_shear, "ok.toml").joint_sets[0].shear_fracture_energy.value_or(-1.0) == 0.0);
  expect_problem(replaced(kValid, "tensile_strength = 7.86e6", "tensile_strength = 7.86e6\nshear_fracture_energy = -5"),
                 "joints.virtual.shear_fracture_energy", 19, "got -5");
  expect_problem(replaced(shear, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nintact_nodes = \"tie\""),
                 "joints.virtual.shear_fracture_energy", 20, "analysis.intact_nodes = \"contact\"");
  expect_problem(replaced(kValid, "tensile_strength = 10", "tensile_strength = 10\nshear_fracture_energy = 80"),
                 "contacts.real_joints", 25, "only virtual joints");
}

BOOST_AUTO_TEST_CASE(mass_damping_is_off_unless_given) {
  BOOST_TEST(scene::parse_scene(kValid, "ok.toml").analysis.mass_damping == 0.0);
  const scene::Scene s = scene::parse_scene(
      replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nmass_damping = 4.8e3"), "ok.toml");
  BOOST_TEST(s.analysis.mass_damping == 4.8e3);
}

BOOST_AUTO_TEST_CASE(negative_mass_damping_is_refused) {
  expect_problem(replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nmass_damping = -1"),
                 "analysis.mass_damping", 11, ">= 0");
}

BOOST_AUTO_TEST_CASE(mass_damping_in_static_mode_is_refused) {
  const std::string static_scene =
      replaced(replaced(kValid, "mode = \"dynamic\"", "mode = \"static\""), "velocity = ", "# velocity = ");
  expect_problem(replaced(static_scene, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nmass_damping = 100"),
                 "analysis.mass_damping", 11, "no effect in static mode");
}

BOOST_AUTO_TEST_CASE(zero_search_distance_is_refused) {
  expect_problem(replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81]\nsearch_distance_factor = 0"),
                 "analysis.search_distance_factor", 11, "> 0");
}

BOOST_AUTO_TEST_CASE(connectivity_outside_open_unit_interval) {
  expect_problem(replaced(kValid, "connectivity = 0.25", "connectivity = 1.0"), "geometry.connectivity", 29,
                 "in (0, 1)");
}

BOOST_AUTO_TEST_CASE(misspelt_choice_suggests_the_closest) {
  expect_problem(replaced(kValid, "mode = \"dynamic\"", "mode = \"dynamc\""), "analysis.mode", 3,
                 "did you mean \"dynamic\"");
}

BOOST_AUTO_TEST_CASE(unknown_generator) {
  expect_problem(replaced(kValid, "\"impact_disc\"", "\"impact\""), "geometry.generator", 26,
                 "did you mean \"impact_disc\"");
}

BOOST_AUTO_TEST_CASE(reference_to_undefined_material) {
  expect_problem(replaced(kValid, "material = \"rock\"\nrole = \"plate\"", "material = \"granite\"\nrole = \"plate\""),
                 "bodies.plate.material", 42, "no materials is named \"granite\"");
}

BOOST_AUTO_TEST_CASE(reference_to_undefined_joint_set) {
  expect_problem(replaced(kValid, "real_joints = \"real\"", "real_joints = \"rael\""), "contacts.real_joints", 24,
                 "did you mean \"real\"");
}

BOOST_AUTO_TEST_CASE(body_the_geometry_does_not_make) {
  // Two problems: the misnamed body, and the geometry's body left undescribed.
  const auto problems = problems_of(replaced(kValid, "[bodies.plate]", "[bodies.platen]"));
  BOOST_TEST_REQUIRE(problems.size() == 2u);
  BOOST_TEST(problems[0].key == "bodies.platen");
  BOOST_TEST(problems[0].message.find("did you mean \"plate\"") != std::string::npos);
  BOOST_TEST(problems[1].key == "bodies.plate");
  BOOST_TEST(problems[1].message.find("describe it in [bodies.plate]") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(prescribed_motion_needs_a_velocity) {
  expect_problem(replaced(kValid, "motion = \"fixed\"", "motion = \"prescribed\""), "bodies.plate.prescribed_velocity",
                 0, "missing required value");
}

BOOST_AUTO_TEST_CASE(prescribed_velocity_without_prescribed_motion) {
  expect_problem(replaced(kValid, "motion = \"fixed\"", "motion = \"fixed\"\nprescribed_velocity = [0, -1]"),
                 "bodies.plate.prescribed_velocity", 45, "motion is not \"prescribed\"");
}

BOOST_AUTO_TEST_CASE(vector_of_wrong_length) {
  expect_problem(replaced(kValid, "gravity = [0.0, -9.81]", "gravity = [0.0, -9.81, 0.0]"), "analysis.gravity", 10,
                 "got an array of 3 values");
}

BOOST_AUTO_TEST_CASE(joint_wider_than_long) {
  expect_problem(replaced(kValid, "joint_width = 0.4e-3", "joint_width = 0.03"), "geometry.joint_width", 30,
                 "smaller than the joint length");
}

BOOST_AUTO_TEST_CASE(output_interval_longer_than_the_run) {
  expect_problem(replaced(kValid, "output_interval = 2e-5", "output_interval = 1"), "analysis.output_interval", 9,
                 "must not exceed analysis.end_time");
}

BOOST_AUTO_TEST_CASE(gauge_outside_the_disc) {
  expect_problem(replaced(kValid, "position = [0.0, -0.045]", "position = [0.0, -0.06]"), "gauges[0].position", 47,
                 "outside the disc");
}

BOOST_AUTO_TEST_CASE(two_gauges_with_one_name) {
  expect_problem(kValid + "[[gauges]]\nname = \"A\"\nposition = [0.0, 0.0]\n", "gauges[1].name", 49,
                 "a second gauge is named \"A\"");
}

BOOST_AUTO_TEST_CASE(friction_angle_of_ninety_degrees) {
  expect_problem(replaced(kValid, "friction_angle = 20", "friction_angle = 90"), "joints.real.friction_angle", 20,
                 "in [0, 90) (degrees)");
}

BOOST_AUTO_TEST_CASE(block_count_must_be_a_whole_number) {
  expect_problem(replaced(kValid, "blocks = 1200", "blocks = 1200.5"), "mesh.blocks", 34, "a whole number");
}

BOOST_AUTO_TEST_CASE(initial_velocity_in_static_mode) {
  expect_problem(replaced(kValid, "mode = \"dynamic\"", "mode = \"static\""), "bodies.disc.velocity", 40,
                 "no effect in static mode");
}

BOOST_AUTO_TEST_CASE(toml_syntax_error_gives_line) {
  const auto problems = problems_of(replaced(kValid, "penalty = 0.35e9", "penalty = = 0.35e9"));
  BOOST_TEST_REQUIRE(problems.size() == 1u);
  BOOST_TEST(problems[0].line == 7);
  BOOST_TEST(problems[0].message.find("not valid TOML") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(geometry_file_and_generator_together) {
  const auto problems =
      problems_of(replaced(kValid, "generator = \"impact_disc\"", "generator = \"impact_disc\"\nfile = \"x.msh\""));
  BOOST_TEST_REQUIRE(!problems.empty());
  BOOST_TEST(problems[0].key == "geometry.file");
  BOOST_TEST(problems[0].message.find("not both") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(several_problems_are_all_reported) {
  std::string text = replaced(kValid, "dt_max = 1e-7", "dt_max = -1");
  text = replaced(text, "poisson = 0.12", "poisson = 0.7");
  text = replaced(text, "role = \"disc\"", "role = \"rock\"");
  const auto problems = problems_of(text);
  BOOST_TEST(problems.size() == 3u);
}

BOOST_AUTO_TEST_CASE(error_text_has_file_line_column_key) {
  try {
    scene::parse_scene(replaced(kValid, "dt_max = 1e-7", "dt_max = 0"), "dir/scene.toml");
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    const std::string text = e.what();
    BOOST_TEST(text.find("dir/scene.toml:5:10: analysis.dt_max: expected a number > 0 (s), got 0") !=
               std::string::npos);
  }
}

// --- base scenes and overrides -------------------------------------------------------------

namespace {
std::filesystem::path write_temp(const std::string& name, const std::string& text) {
  const auto dir = std::filesystem::temp_directory_path() / "ddafrac_scene_test";
  std::filesystem::create_directories(dir);
  const auto path = dir / name;
  std::ofstream(path) << text;
  return path;
}
}  // namespace

BOOST_AUTO_TEST_CASE(derived_scene_overrides_its_base_and_blames_the_right_file) {
  write_temp("base.toml", kValid);
  const auto derived = write_temp("derived.toml", "base = \"base.toml\"\n[analysis]\nend_time = 3e-3\n");
  const scene::Scene s = scene::load_scene(derived);
  BOOST_TEST(s.analysis.end_time == 3e-3);
  BOOST_TEST(s.analysis.dt_max == 1e-7);  // from the base

  write_temp("base_bad.toml", replaced(kValid, "density = 2050", "density = -1"));
  const auto derived_bad = write_temp("derived_bad.toml", "base = \"base_bad.toml\"\n");
  try {
    scene::load_scene(derived_bad);
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    BOOST_TEST_REQUIRE(e.problems().size() == 1u);
    BOOST_TEST(e.problems()[0].file.find("base_bad.toml") != std::string::npos);
    BOOST_TEST(e.problems()[0].line == 12);
  }
}

BOOST_AUTO_TEST_CASE(base_cycle_is_refused) {
  const auto a = write_temp("cycle_a.toml", "base = \"cycle_b.toml\"\n");
  write_temp("cycle_b.toml", "base = \"cycle_a.toml\"\n");
  try {
    scene::load_scene(a);
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    BOOST_TEST(std::string(e.what()).find("nested base scenes") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(missing_file_is_named) {
  try {
    scene::load_scene("/nonexistent/scene.toml");
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    BOOST_TEST(std::string(e.what()).find("/nonexistent/scene.toml: cannot read") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(overrides_replace_values_before_validation) {
  const auto path = write_temp("plain.toml", kValid);
  const scene::Scene s = scene::load_scene(
      path, {"analysis.dt_max=1e-8", "analysis.mode=static", "bodies.disc.velocity=[0.0, 0.0]", "mesh.blocks=500"});
  BOOST_TEST(s.analysis.dt_max == 1e-8);
  BOOST_TEST((s.analysis.mode == scene::Mode::Static));
  BOOST_TEST(s.mesh.target_blocks == 500);

  try {
    scene::load_scene(path, {"analysis.dt_max=-1"});
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    BOOST_TEST_REQUIRE(e.problems().size() == 1u);
    BOOST_TEST(e.problems()[0].key == "analysis.dt_max");
    BOOST_TEST(e.problems()[0].file == "--set analysis.dt_max=-1");
  }
  try {
    scene::load_scene(path, {"analysis.dt_max"});
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    BOOST_TEST(std::string(e.what()).find("expected key=value") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(bad_sweep_file_reports_every_problem) {
  const auto path = write_temp("sweep.toml", "cases = [\"missing.toml\", 3]\ncrack_tim = 1e-3\n");
  try {
    scene::load_sweep(path);
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    const auto& p = e.problems();
    BOOST_TEST_REQUIRE(p.size() == 3u);
    BOOST_TEST(p[0].key == "crack_time");  // missing
    BOOST_TEST(p[1].key == "cases");
    BOOST_TEST(p[1].line == 1);
    BOOST_TEST(p[1].message.find("got a number") != std::string::npos);
    BOOST_TEST(p[2].message.find("did you mean \"crack_time\"") != std::string::npos);
  }
  write_temp("one.toml", kValid);
  const auto missing = write_temp("sweep2.toml", "cases = [\"one.toml\", \"two.toml\"]\ncrack_time = 1e-3\n");
  try {
    scene::load_sweep(missing);
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    BOOST_TEST_REQUIRE(e.problems().size() == 1u);
    BOOST_TEST(e.problems()[0].message.find("two.toml") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(verification_tolerances_are_read_and_a_missing_table_means_none) {
  BOOST_TEST(!scene::parse_scene(kValid, "ok.toml").verification.has_value());
  const scene::Scene s =
      scene::parse_scene(kValid + "[verification]\nload = 1e6\nfield_l2 = 0.1\narrival_time = 0.05\n", "ok.toml");
  BOOST_TEST_REQUIRE(s.verification.has_value());
  BOOST_TEST(s.verification->load.value() == 1e6);
  BOOST_TEST(s.verification->field_l2.value() == 0.1);
  BOOST_TEST(s.verification->arrival_time.value() == 0.05);
  BOOST_TEST(!s.verification->centre_stress.has_value());
}

BOOST_AUTO_TEST_CASE(negative_verification_tolerance_is_refused) {
  expect_problem(kValid + "[verification]\ngauge_rms = -0.2\n", "verification.gauge_rms", 49,
                 "> 0 (relative error), got -0.2");
}

// --- names that become folders and CSV fields; what toml++ is handed (issue 13) ----------

namespace {

/// Loads the scene at `path` with `overrides` and returns the problems it was refused for.
std::vector<scene::Problem> load_problems(const std::filesystem::path& path,
                                          const std::vector<std::string>& overrides = {}) {
  try {
    scene::load_scene(path, overrides);
  } catch (const scene::SceneError& e) {
    return e.problems();
  }
  BOOST_FAIL("the scene was accepted");
  return {};
}

}  // namespace

BOOST_AUTO_TEST_CASE(a_scene_name_cannot_climb_out_of_the_output_folder) {
  expect_problem(replaced(kValid, "name = \"t\"", "name = \"../../x\""), "name", 1,
                 "the character \"/\" is not allowed");
}

BOOST_AUTO_TEST_CASE(a_gauge_name_cannot_break_the_columns_of_gauges_csv) {
  expect_problem(replaced(kValid, "name = \"A\"", "name = \"A,B\""), "gauges[0].name", 46, "\",\" is not allowed");
}

BOOST_AUTO_TEST_CASE(a_file_name_that_is_not_utf8_cannot_stand_in_for_the_name) {
  try {
    scene::parse_scene(replaced(kValid, "name = \"t\"\n", ""), "\xff\xfe.toml");
    BOOST_FAIL("accepted");
  } catch (const scene::SceneError& e) {
    BOOST_TEST_REQUIRE(e.problems().size() == 1u);
    BOOST_TEST(e.problems()[0].key == "name");
    BOOST_TEST(e.problems()[0].message.find("not valid UTF-8") != std::string::npos);
  }
}

BOOST_AUTO_TEST_CASE(a_dotted_key_of_a_hundred_thousand_parts_is_refused_before_toml_parses_it) {
  std::string deep = "a";
  for (int i = 0; i < 100000; ++i) deep += ".a";
  expect_problem(kValid + deep + " = 1\n", "", 48, "a key of more than 64 dotted parts");
}

BOOST_AUTO_TEST_CASE(a_crack_interval_that_cuts_the_run_into_too_many_pieces_is_refused) {
  expect_problem(kValid + "[output]\ncrack_interval = 1e-300\n", "output.crack_interval", 49, "more than 100000");
}

BOOST_AUTO_TEST_CASE(a_bad_set_value_is_blamed_on_the_option_without_a_line) {
  const auto p = load_problems(write_temp("plain_set.toml", kValid), {"analysis.mode=statc", "outptu.vtk=true"});
  BOOST_TEST_REQUIRE(p.size() == 2u);
  BOOST_TEST(p[0].file == "--set analysis.mode=statc");
  BOOST_TEST(p[0].line == 0);
  BOOST_TEST(p[1].file == "--set outptu.vtk=true");
  BOOST_TEST(p[1].message.find("did you mean \"output\"") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(a_scene_file_of_two_megabytes_is_refused_unread) {
  const auto p = load_problems(write_temp("huge.toml", kValid + "#" + std::string(2u << 20, 'x') + "\n"));
  BOOST_TEST_REQUIRE(p.size() == 1u);
  BOOST_TEST(p[0].message.find("too long for a scene (at most 1048576 bytes)") != std::string::npos);
}
