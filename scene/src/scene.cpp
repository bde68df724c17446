#include "ddafrac/scene/scene.hpp"

namespace ddafrac::scene {

const Body* Scene::find_body(const std::string& body_name) const {
  for (const Body& body : bodies)
    if (body.name == body_name) return &body;
  return nullptr;
}

}  // namespace ddafrac::scene
