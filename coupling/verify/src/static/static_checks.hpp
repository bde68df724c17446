#pragma once
// The static comparison's numbers against the tolerances of the scene's [verification] table:
// the centre stresses (centre_stress) and the field error (field_l2), against the FEM and,
// where the Hondros series applies, against it too.

#include <vector>

#include "ddafrac/coupling/verification.hpp"
#include "ddafrac/scene/scene.hpp"
#include "static/static_compare.hpp"

namespace ddafrac::coupling {

std::vector<Check> static_checks(const StaticSetup& setup, const StaticComparison& comparison,
                                 const scene::Verification& tolerances);

}  // namespace ddafrac::coupling
