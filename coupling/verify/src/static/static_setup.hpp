#pragma once
// What the static comparison takes from the scene: the disc, and the one load both models carry
// (a pressure on the Hondros arcs of a plain or slit disc, or on the flats of a flattened disc).

#include <optional>

#include "ddafrac/meshes/geometry.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

struct StaticSetup {
  double diameter = 0.0;  // m
  double radius = 0.0;    // m
  bool flattened = false;
  double half_angle = 0.0;  // rad: of the Hondros arcs (plain/slit disc), or half the flat angle (flattened)
  double load = 0.0;        // N/m, nominal diametral load P
  double pressure = 0.0;    // Pa, on the arcs or the flats
  std::optional<meshes::Slit> slit;
  bool analytic = false;                        // the Hondros series applies (plain disc without slit)
  meshes::Geometry dda_geometry, fem_geometry;  // flattened disc: without its platens
};

/// Throws std::invalid_argument for a scene that is not a plain, flattened or slit disc.
StaticSetup static_setup(const scene::Scene& scene);

}  // namespace ddafrac::coupling
