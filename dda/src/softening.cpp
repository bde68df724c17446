#include "ddafrac/dda/softening.hpp"

#include <cmath>

namespace ddafrac::dda {

double softening_ductility(double fracture_energy, double tensile_strength, double stiffness, double length) {
  if (tensile_strength <= 0.0 || length <= 0.0) return 0.0;
  const double spent_opening = 2.0 * fracture_energy / tensile_strength;  // δc, m
  const double peak_opening = tensile_strength * length / stiffness;      // δ0, m
  return spent_opening / peak_opening;
}

double mixed_mode_ductility(double r1, double r2, double tensile_ductility, double shear_ductility) {
  if (!std::isfinite(r1) || !std::isfinite(r2)) return 0.0;     // loaded in a mode without strength
  const double tension_share = r1 * r1, shear_share = r2 * r2;  // of r1² + r2², the mix cos²α, sin²α
  if (tension_share + shear_share <= 0.0) return tensile_ductility;
  if ((tension_share > 0.0 && tensile_ductility <= 0.0) || (shear_share > 0.0 && shear_ductility <= 0.0)) return 0.0;
  const double inverse = (tension_share > 0.0 ? tension_share / tensile_ductility : 0.0) +
                         (shear_share > 0.0 ? shear_share / shear_ductility : 0.0);
  return (tension_share + shear_share) / inverse;
}

double softening_damage(double drive, double ductility) {
  if (drive <= 1.0) return 0.0;
  if (ductility <= 1.0 || drive >= ductility) return 1.0;
  // Secant of the linear branch: (1 − D)·x = (μ − x)/(μ − 1), the force over the strength.
  return 1.0 - (ductility - drive) / (drive * (ductility - 1.0));
}

}  // namespace ddafrac::dda
