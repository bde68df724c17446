#include "ddafrac/coupling/dda_twin.hpp"

#include <limits>
#include <stdexcept>

namespace ddafrac::coupling {

const scene::Body& disc_body(const scene::Scene& s) {
  for (const auto& b : s.bodies)
    if (b.role == scene::Role::Disc) return b;
  throw std::runtime_error(s.source.string() + ": the scene has no disc body");
}

DdaTwin bonded_dda_twin(const scene::Scene& scene, double kn_over_young) {
  const scene::Body& disc = disc_body(scene);
  if (!disc.virtual_joints) throw std::runtime_error(scene.source.string() + ": the disc has no virtual joints");
  DdaTwin twin{scene};
  if (kn_over_young > 0.0) {
    const double kn = kn_over_young * scene.materials.at(disc.material).young;
    for (auto& js : twin.scene.joint_sets) {
      if (!(js.normal_stiffness > 0.0))
        throw std::runtime_error(scene.source.string() + ": joint set '" + js.name + "' has no normal stiffness");
      const double ks_over_kn = js.shear_stiffness / js.normal_stiffness;
      js.normal_stiffness = kn;
      js.shear_stiffness = ks_over_kn * kn;
    }
  }
  auto& bonded = twin.scene.joint_sets.at(*disc.virtual_joints);
  bonded.tensile_strength = std::numeric_limits<double>::infinity();  // failure ratios are then 0
  bonded.cohesion = std::numeric_limits<double>::infinity();
  twin.kn = bonded.normal_stiffness;
  twin.ks_over_kn = bonded.shear_stiffness / bonded.normal_stiffness;
  twin.scene.analysis.penalty = twin.kn;
  twin.scene.analysis.gravity = {0.0, 0.0};
  return twin;
}

}  // namespace ddafrac::coupling
