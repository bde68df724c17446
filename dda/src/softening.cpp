#include "ddafrac/dda/softening.hpp"

namespace ddafrac::dda {

double softening_ductility(double fracture_energy, double tensile_strength, double stiffness, double length) {
  if (tensile_strength <= 0.0 || length <= 0.0) return 0.0;
  const double spent_opening = 2.0 * fracture_energy / tensile_strength;  // δc, m
  const double peak_opening = tensile_strength * length / stiffness;      // δ0, m
  return spent_opening / peak_opening;
}

double softening_damage(double drive, double ductility) {
  if (drive <= 1.0) return 0.0;
  if (ductility <= 1.0 || drive >= ductility) return 1.0;
  // Secant of the linear branch: (1 − D)·x = (μ − x)/(μ − 1), the force over the strength.
  return 1.0 - (ductility - drive) / (drive * (ductility - 1.0));
}

}  // namespace ddafrac::dda
