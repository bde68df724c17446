// Every ready scene in scenes/ parses, and the study's cases carry the study's parameters
// (source study).
#define BOOST_TEST_MODULE scene_files
#include <boost/test/unit_test.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/scene/parse.hpp"
#include "ddafrac/scene/sweep.hpp"

using namespace ddafrac;
namespace fs = std::filesystem;

namespace {
constexpr double kDegree = common::kRadiansPerDegree;
const fs::path kScenes = fs::path(DDAFRAC_SOURCE_DIR) / "scenes";
}  // namespace

BOOST_AUTO_TEST_CASE(every_scene_file_parses) {
  int parsed = 0;
  for (const auto& entry : fs::recursive_directory_iterator(kScenes)) {
    const std::string name = entry.path().filename().string();
    const bool sweep = name.size() > 11 && name.compare(name.size() - 11, 11, ".sweep.toml") == 0;
    if (entry.path().extension() != ".toml" || name.rfind("common_", 0) == 0 || sweep) continue;
    BOOST_TEST_CONTEXT(entry.path().string()) { BOOST_CHECK_NO_THROW(scene::load_scene(entry.path())); }
    ++parsed;
  }
  // 15 impact cases + base, 3 flattened + 4 pre-cracked + 2 bases, 4 small, default.
  BOOST_TEST(parsed >= 30);
}

BOOST_AUTO_TEST_CASE(impact_cases_match_the_study_table) {
  const double theta[] = {0, 15, 30, 45, 60, 75, 90, 45, 45, 45, 45, 45, 45, 45, 45};
  const double gamma[] = {0.25, 0.25, 0.25, 0.25, 0.25, 0.25, 0.25, 0.25, 0.5, 0.75, 0.25, 0.25, 0.25, 0.25, 0.25};
  const double v0[] = {3.5, 3.5, 3.5, 3.5, 3.5, 3.5, 3.5, 3.5, 3.5, 3.5, 3.0, 3.5, 4.0, 5.0, 6.0};
  for (int i = 0; i < 15; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "case%02d.toml", i + 1);
    BOOST_TEST_CONTEXT(name) {
      const scene::Scene s = scene::load_scene(kScenes / "impact" / name);
      const auto& g = std::get<meshes::ImpactDisc>(s.geometry);
      BOOST_TEST(std::abs(g.joint_angle - theta[i] * kDegree) < 1e-12);
      BOOST_TEST(g.connectivity == gamma[i]);
      BOOST_TEST(g.joint_width == 0.4e-3);
      BOOST_TEST(s.bodies[0].initial_velocity[1] == -v0[i]);
      BOOST_TEST(s.analysis.penalty == 0.35e9);
      BOOST_TEST(s.analysis.end_time == (v0[i] == 6.0 ? 3.0e-3 : 1.8e-3));
      BOOST_TEST(s.gauges.size() == 8u);
      BOOST_TEST(s.mesh.target_blocks == 5550);
    }
  }
}

BOOST_AUTO_TEST_CASE(brazilian_scenes_match_the_study) {
  for (int blocks : {2045, 4107, 6081}) {
    const scene::Scene s = scene::load_scene(kScenes / "brazilian" / ("flattened_" + std::to_string(blocks) + ".toml"));
    BOOST_TEST(s.mesh.target_blocks == blocks);
    BOOST_TEST(s.analysis.penalty == 10e9);
    const auto& g = std::get<meshes::FlattenedDisc>(s.geometry);
    BOOST_TEST(std::abs(g.flat_angle - 10 * kDegree) < 1e-12);
    BOOST_TEST(!g.slit.has_value());
  }
  for (int angle : {30, 45, 60, 75}) {
    const scene::Scene s = scene::load_scene(kScenes / "brazilian" / ("precracked_" + std::to_string(angle) + ".toml"));
    const auto& g = std::get<meshes::FlattenedDisc>(s.geometry);
    BOOST_TEST_REQUIRE(g.slit.has_value());
    BOOST_TEST(g.slit->length == 0.025);
    BOOST_TEST(std::abs(g.slit->inclination - angle * kDegree) < 1e-12);
    BOOST_TEST(s.mesh.target_blocks == 4000);
  }
}

BOOST_AUTO_TEST_CASE(impact_sweep_lists_the_fifteen_cases) {
  const scene::Sweep sweep = scene::load_sweep(kScenes / "impact" / "cases.sweep.toml");
  BOOST_TEST(sweep.cases.size() == 15u);
  BOOST_TEST(sweep.crack_time == 1.8e-3);
  BOOST_TEST(sweep.threads == 1);
  for (const auto& file : sweep.cases) BOOST_TEST(fs::exists(file));
}

// The source study as a sweep (for mpirun and --emit-slurm): the 3 flattened, 4 pre-cracked and
// 15 impact scenes of `ddafrac study source`, one thread each.
BOOST_AUTO_TEST_CASE(source_study_sweep_lists_the_twenty_two_cases) {
  const scene::Sweep sweep = scene::load_sweep(kScenes / "source_study.sweep.toml");
  BOOST_TEST(sweep.cases.size() == 22u);
  BOOST_TEST(sweep.threads == 1);
  const auto in = [&](const char* folder) {
    return std::count_if(sweep.cases.begin(), sweep.cases.end(),
                         [&](const fs::path& file) { return file.parent_path().filename() == folder; });
  };
  BOOST_TEST(in("brazilian") == 7);
  BOOST_TEST(in("impact") == 15);
  for (const auto& file : sweep.cases) BOOST_TEST(fs::exists(file));
}
