// Full-size study cases (label `slow`, not run in CI).
#define BOOST_TEST_MODULE dda_full_size
#include <boost/test/unit_test.hpp>

#include "energy_checks.hpp"

// Impact case 4 at full size (~5550 blocks, 1800 µs) gained 30% (stored energy 127.85 J/m at
// 336 µs against 98.47 J/m at the start) with 162 568 contacts found already overlapping. Same
// bounds as the default scene's test in dda_scenes.
BOOST_AUTO_TEST_CASE(impact_case_4_at_full_size_never_gains_energy) {
  ddafrac::dda::testing::check_never_gains_energy(std::filesystem::path(DDAFRAC_SOURCE_DIR) /
                                                  "scenes/impact/case04.toml");
}
