#pragma once
// Polygon integrals in closed form and the DDA displacement function T (docs/design.md §2).

#include <cmath>
#include <cstddef>

#include "ddafrac/dda/types.hpp"

namespace ddafrac::dda {

/// Area, centroid and second moments about the centroid of a simple polygon (CCW: area > 0).
struct PolygonIntegrals {
  double area = 0.0;  // m^2 (per unit thickness)
  double cx = 0.0;    // m
  double cy = 0.0;    // m
  double sxx = 0.0;   // ∫(x-x0)^2 dA, m^4
  double syy = 0.0;   // ∫(y-y0)^2 dA, m^4
  double sxy = 0.0;   // ∫(x-x0)(y-y0) dA, m^4
};

/// Closed-form integrals (Green's theorem over the edges), computed relative to the first vertex
/// so that small blocks far from the origin keep their precision.
PolygonIntegrals polygon_integrals(const double* x, const double* y, std::size_t n);

/// T(x, y) of a block with centroid (cx, cy): displacement of the point = T · D.
inline Mat26 displacement_matrix(double cx, double cy, double px, double py) {
  const double dx = px - cx;
  const double dy = py - cy;
  Mat26 t;
  t << 1.0, 0.0, -dy, dx, 0.0, 0.5 * dy,  //
      0.0, 1.0, dx, 0.0, dy, 0.5 * dx;
  return t;
}

/// ∫ T^T T dA over the block (multiply by the density for the mass matrix).
Mat6 mass_integral(const PolygonIntegrals& g);

/// New position of a point of a block after the block displacement D: rigid rotation by r0 is
/// applied exactly (no spurious growth of rotating blocks), translation and strain linearly.
inline void displace_point(double cx, double cy, const Vec6& d, double& px, double& py) {
  const double dx = px - cx;
  const double dy = py - cy;
  const double c = std::cos(d[kR]);
  const double s = std::sin(d[kR]);
  const double nx = cx + d[kU] + c * dx - s * dy + d[kEx] * dx + 0.5 * d[kGxy] * dy;
  const double ny = cy + d[kV] + s * dx + c * dy + 0.5 * d[kGxy] * dx + d[kEy] * dy;
  px = nx;
  py = ny;
}

}  // namespace ddafrac::dda
