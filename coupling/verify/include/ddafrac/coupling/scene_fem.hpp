#pragma once
// How a scene becomes a FEM problem: the disc's material and plane model, its diameter, and
// the conventions of the static load (shared by `ddafrac fem` and `ddafrac verify`).

#include "ddafrac/common/angles.hpp"
#include "ddafrac/fem/elasticity.hpp"
#include "ddafrac/meshes/geometry.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

/// Diameter of a generated disc geometry; throws std::invalid_argument for a user .msh file.
double disc_diameter(const meshes::Geometry& geometry);

/// Material of the scene's disc body with the scene's plane model; throws
/// std::invalid_argument if the scene has no disc body.
fem::Material disc_material(const scene::Scene& scene);

/// Default FEM element size: the disc's diameter over this (`ddafrac fem`, `ddafrac verify`).
inline constexpr double kFemElementsPerDiameter = 25.0;

/// Default half-angle (rad) of the Hondros arcs of a disc whose geometry has none.
inline constexpr double default_arc_half_angle = 10.0 * common::kPi / 180.0;

}  // namespace ddafrac::coupling
