#include "ddafrac/coupling/verify_static.hpp"

#include <stdexcept>

#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

VerificationReport verify_static(const scene::Scene& scene, const VerifyOptions&) {
  throw std::runtime_error(scene.name + ": static verification not implemented yet");
}

}  // namespace ddafrac::coupling
