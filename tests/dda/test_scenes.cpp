// Scene-level checks of the DDA engine on the study's own scene files (meshed by gmsh).
#define BOOST_TEST_MODULE dda_scenes
#include <boost/test/unit_test.hpp>

#include <string>
#include <vector>

#include "ddafrac/dda/engine.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "ddafrac/scene/parse.hpp"

using namespace ddafrac;
using namespace ddafrac::dda;

namespace {
std::filesystem::path scene_file(const std::string& rel) { return std::filesystem::path(DDAFRAC_SOURCE_DIR) / rel; }
}  // namespace

// Regression: the default scene (1200-block glued impact disc with a joint slot) ended in
// numerical trouble at t ≈ 18.8 µs (a contact flipping locked <-> sliding, dt down to 4e-14 s).
// Its first 40 µs now need no dt cut at all.
BOOST_AUTO_TEST_CASE(default_scene_first_40us_without_dt_cuts) {
  const scene::Scene sc = scene::load_scene(scene_file("scenes/default.toml"), {});
  const meshes::Mesh mesh = meshes::generate_dda_mesh(sc.geometry, sc.mesh);
  Engine e(sc, mesh);
  while (e.time() < 40e-6 * (1.0 - 1e-9)) e.step(40e-6 - e.time());
  const Statistics& st = e.statistics();
  BOOST_TEST_MESSAGE("steps " << st.steps << ", cuts " << st.cuts_open_close << " open-close, " << st.cuts_displacement
                              << " displacement, open-close max " << st.open_close_max);
  BOOST_TEST(st.cuts_open_close == 0);
  BOOST_TEST(st.cuts_displacement == 0);
  BOOST_TEST(st.steps == 400);
}
