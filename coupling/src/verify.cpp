#include "ddafrac/coupling/verify.hpp"

#include <stdexcept>

#include "ddafrac/coupling/verify_static.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

std::vector<std::string> missing_tolerances(const scene::Scene&) { return {}; }

VerificationReport verify_scene(const scene::Scene& scene, const VerifyOptions& options) {
  return verify_static(scene, options);
}

}  // namespace ddafrac::coupling
