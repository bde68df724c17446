#include "ddafrac/coupling/scene_fem.hpp"

#include <stdexcept>
#include <variant>

namespace ddafrac::coupling {

double disc_diameter(const meshes::Geometry& g) {
  if (const auto* d = std::get_if<meshes::PlainDisc>(&g)) return d->diameter;
  if (const auto* d = std::get_if<meshes::FlattenedDisc>(&g)) return d->diameter;
  if (const auto* d = std::get_if<meshes::SlitDisc>(&g)) return d->diameter;
  if (const auto* d = std::get_if<meshes::ImpactDisc>(&g)) return d->diameter;
  throw std::invalid_argument("the FEM reference needs a generated disc geometry (not a user .msh file)");
}

fem::Material disc_material(const scene::Scene& s) {
  const scene::Body* disc = nullptr;
  for (const auto& b : s.bodies)
    if (b.role == scene::Role::Disc) disc = &b;
  if (!disc) throw std::invalid_argument("the scene has no disc body");
  const auto& m = s.materials.at(disc->material);
  fem::Material out;
  out.elastic = {m.young, m.poisson, m.density};
  out.plane = s.analysis.plane;
  return out;
}

}  // namespace ddafrac::coupling
