#pragma once
// The impact comparison's numbers against the tolerances of the scene's [verification] table:
// the P-wave arrival at every gauge whose arrival is checked (arrival_time) and the σyy history
// at every gauge (gauge_rms).

#include <vector>

#include "ddafrac/coupling/impact_compare.hpp"
#include "ddafrac/coupling/verification.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

std::vector<Check> impact_checks(const std::vector<GaugeError>& errors, const scene::Verification& tolerances);

}  // namespace ddafrac::coupling
