#pragma once
// Analytic reference solutions of the Brazilian disc test and of elastic waves. Part of the
// leaf library ddafrac::reference (closed forms and error measures), which depends on nothing
// but common/: the FEM (fem/), the DDA and the comparisons of coupling/ may all use it. No
// deal.II, no Eigen: plain doubles.
//
// Conventions: SI units, tension positive, 2D (per unit thickness unless `thickness` is given).
// The disc has its centre at the origin and is loaded along the y axis (top point (0, R),
// bottom point (0, -R)); loads are compressive and given as positive magnitudes.

#include "ddafrac/common/plane_model.hpp"

namespace ddafrac::reference {

/// In-plane stress tensor (Pa).
struct Stress2 {
  double xx = 0.0;
  double yy = 0.0;
  double xy = 0.0;
};

/// Principal stresses s1 >= s3 (Pa) and the angle (rad, counter-clockwise from x) of s1.
struct Principal {
  double s1 = 0.0;
  double s3 = 0.0;
  double angle = 0.0;
};

Principal principal(const Stress2& s);

struct Disc {
  double diameter = 0.1;   // m
  double thickness = 1.0;  // m (1 = per unit thickness)
  double radius() const { return 0.5 * diameter; }
};

/// A concentrated compressive force `force` (N) acting radially inwards at the rim point at
/// polar angle `angle` (rad, counter-clockwise from x). Flamant field plus the uniform tension
/// force/(pi*D*t): a sum of such forces that is in equilibrium leaves the rim traction free.
Stress2 radial_rim_force_stress(const Disc& disc, double force, double angle, double x, double y);

/// Classic diametral point-load solution (forces `load` at (0, R) and (0, -R)).
/// Centre: sxx = 2P/(pi D t), syy = -6P/(pi D t).
Stress2 point_load_stress(const Disc& disc, double load, double x, double y);

/// Hondros loading: uniform radial pressure p on the two rim arcs of half-angle alpha about the
/// top and bottom points. The nominal load is P = 2 alpha R t p (pressure times arc length).
struct HondrosLoad {
  double load = 0.0;        // P, N
  double half_angle = 0.0;  // alpha, rad, in (0, pi/2)
  double pressure(const Disc& disc) const;
};

/// Closed form on the loaded diameter (x = 0, |y| < R) (Hondros 1959).
Stress2 hondros_loaded_diameter(const Disc& disc, const HondrosLoad& load, double y);
/// Closed form on the horizontal diameter (y = 0, |x| <= R).
Stress2 hondros_horizontal_diameter(const Disc& disc, const HondrosLoad& load, double x);
/// Centre: sxx = (2p/pi)(sin 2a - a), syy = -(2p/pi)(sin 2a + a).
Stress2 hondros_centre(const Disc& disc, const HondrosLoad& load);

/// Full field from the Fourier series of Hondros, summed until the terms fall below
/// 1e-16 of the leading one (r < R); on the rim itself the series converges slowly, so points
/// with r/R > 1 - 1e-6 are evaluated at r/R = 1 - 1e-6.
Stress2 hondros_series(const Disc& disc, const HondrosLoad& load, double x, double y);

/// Full field as a superposition of radial rim forces (Gauss-Legendre over each arc with
/// `points_per_arc` points): an independent check of the series away from the loaded arcs.
Stress2 hondros_superposition(const Disc& disc, const HondrosLoad& load, double x, double y, int points_per_arc = 400);

/// Flattened disc (flats of central angle `flat_angle`, total flat load P): the arc-mapped
/// approximation, i.e. Hondros loading on arcs of the same central angle carrying the same
/// vertical resultant (p = P / (2 R t sin alpha)), evaluated at the centre.
Stress2 flattened_disc_centre_arc_mapped(const Disc& disc, double load, double flat_angle);

using common::PlaneModel;

struct Elastic {
  double young = 0.0;    // Pa
  double poisson = 0.0;  // -
  double density = 0.0;  // kg/m^3
};

/// Speed of the dilatational (P) wave in the plane model (m/s):
/// plane stress sqrt(E / (rho (1 - nu^2))), plane strain sqrt(E (1 - nu) / (rho (1 + nu)(1 - 2 nu))).
double p_wave_speed(const Elastic& material, PlaneModel plane);
/// Speed of the shear wave sqrt(E / (2 rho (1 + nu))) (m/s), the same in both plane models.
double s_wave_speed(const Elastic& material);

/// Normal stress behind a plane P wave launched by stopping a body moving at v0 against a
/// rigid wall: -rho c_p v0 (Pa, compressive).
double impact_plane_wave_stress(const Elastic& material, PlaneModel plane, double v0);

}  // namespace ddafrac::reference
