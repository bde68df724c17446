#include "ddafrac/scene/scene.hpp"

namespace ddafrac::scene {

const char* to_string(IntactNodes nodes) { return nodes == IntactNodes::Tie ? "tie" : "contact"; }

const char* to_string(FractureLoad load) {
  return load == FractureLoad::BlockStress ? "block_stress" : "joint_springs";
}

const char* to_string(ModeInteraction interaction) {
  return interaction == ModeInteraction::Quadratic ? "quadratic" : "none";
}

const Body* Scene::find_body(const std::string& body_name) const {
  for (const Body& body : bodies)
    if (body.name == body_name) return &body;
  return nullptr;
}

}  // namespace ddafrac::scene
