#include "static/static_setup.hpp"

#include <cmath>
#include <stdexcept>
#include <variant>

#include "ddafrac/coupling/scene_fem.hpp"

namespace ddafrac::coupling {

StaticSetup static_setup(const scene::Scene& s) {
  StaticSetup out;
  out.diameter = disc_diameter(s.geometry);
  out.radius = 0.5 * out.diameter;
  out.load = *s.verification->load;
  out.dda_geometry = out.fem_geometry = s.geometry;
  if (auto* flat = std::get_if<meshes::FlattenedDisc>(&out.dda_geometry)) {
    flat->with_platens = false;  // loaded on the flats directly, like the FEM
    std::get<meshes::FlattenedDisc>(out.fem_geometry).with_platens = false;
    out.flattened = true;
    out.half_angle = 0.5 * flat->flat_angle;
    out.pressure = out.load / (out.diameter * std::sin(out.half_angle));  // load / flat width
    out.slit = flat->slit;
  } else if (const auto* plain = std::get_if<meshes::PlainDisc>(&s.geometry)) {
    out.half_angle = plain->load_half_angle > 0.0 ? plain->load_half_angle : default_arc_half_angle;
    out.pressure = out.load / (out.half_angle * out.diameter);  // P = 2αR p
    out.analytic = true;
  } else if (const auto* slit = std::get_if<meshes::SlitDisc>(&s.geometry)) {
    out.half_angle = default_arc_half_angle;
    out.pressure = out.load / (out.half_angle * out.diameter);
    out.slit = slit->slit;
  } else {
    throw std::invalid_argument(
        "verify_static: the scene is not a static Brazilian disc (plain, flattened or slit disc)");
  }
  return out;
}

}  // namespace ddafrac::coupling
