#pragma once
// The DDA twin of the continuum: the scene's DDA model of its disc with the virtual joints bonded
// and unbreakable, so that the blocks deform as one elastic body to be compared with the FEM of
// the same body. The static and the dynamic comparison build their twins here; this is the one
// place that sets a twin's joint stiffnesses.

#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

struct DdaTwin {
  scene::Scene scene;
  double kn = 0.0;          // N/m, normal stiffness of the bonded virtual joints (also analysis.penalty)
  double ks_over_kn = 0.0;  // shear / normal stiffness of the bonded virtual joints
};

/// The twin of `scene`: the disc's virtual joints never break (σt = c = ∞), gravity is off, and
/// every joint set gets kn = kn_over_young · E (E of the disc) and keeps its own ks/kn, which is
/// the scene's (the parser's default when the file gives no shear_stiffness); kn_over_young <= 0
/// keeps the scene's stiffnesses. The analysis penalty becomes the joints' kn. Mode, time step
/// and bodies are the caller's to set. Throws std::runtime_error when the scene has no disc body
/// or its disc has no virtual joints.
DdaTwin bonded_dda_twin(const scene::Scene& scene, double kn_over_young);

/// The scene's first body of role disc; throws std::runtime_error naming the file if it has none.
const scene::Body& disc_body(const scene::Scene& scene);

}  // namespace ddafrac::coupling
