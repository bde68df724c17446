#include "ddafrac/dda/geometry.hpp"

namespace ddafrac::dda {

PolygonIntegrals polygon_integrals(const double* x, const double* y, std::size_t n) {
  PolygonIntegrals g;
  if (n < 3) return g;
  const double ox = x[0];
  const double oy = y[0];
  double a2 = 0.0;  // 2 A
  double qx = 0.0;  // 6 A cx'
  double qy = 0.0;
  double ixx = 0.0;  // 12 ∫x'^2
  double iyy = 0.0;  // 12 ∫y'^2
  double ixy = 0.0;  // 24 ∫x'y'
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t k1 = (k + 1 == n) ? 0 : k + 1;
    const double x0 = x[k] - ox;
    const double y0 = y[k] - oy;
    const double x1 = x[k1] - ox;
    const double y1 = y[k1] - oy;
    const double c = x0 * y1 - x1 * y0;
    a2 += c;
    qx += (x0 + x1) * c;
    qy += (y0 + y1) * c;
    ixx += (x0 * x0 + x0 * x1 + x1 * x1) * c;
    iyy += (y0 * y0 + y0 * y1 + y1 * y1) * c;
    ixy += (x0 * y1 + 2.0 * x0 * y0 + 2.0 * x1 * y1 + x1 * y0) * c;
  }
  const double area = 0.5 * a2;
  g.area = area;
  if (area == 0.0) {
    g.cx = ox;
    g.cy = oy;
    return g;
  }
  const double cx = qx / (3.0 * a2);
  const double cy = qy / (3.0 * a2);
  g.cx = ox + cx;
  g.cy = oy + cy;
  g.sxx = ixx / 12.0 - area * cx * cx;
  g.syy = iyy / 12.0 - area * cy * cy;
  g.sxy = ixy / 24.0 - area * cx * cy;
  return g;
}

Mat6 mass_integral(const PolygonIntegrals& g) {
  // T = [[1,0,-Y,X,0,Y/2],[0,1,X,0,Y,X/2]] with X, Y about the centroid: first moments vanish.
  const double s = g.area;
  const double xx = g.sxx;
  const double yy = g.syy;
  const double xy = g.sxy;
  Mat6 m = Mat6::Zero();
  m(0, 0) = s;
  m(1, 1) = s;
  m(2, 2) = xx + yy;
  m(2, 3) = -xy;
  m(2, 4) = xy;
  m(2, 5) = 0.5 * (xx - yy);
  m(3, 3) = xx;
  m(3, 5) = 0.5 * xy;
  m(4, 4) = yy;
  m(4, 5) = 0.5 * xy;
  m(5, 5) = 0.25 * (xx + yy);
  for (int r = 0; r < 6; ++r)
    for (int c = 0; c < r; ++c) m(r, c) = m(c, r);
  return m;
}

}  // namespace ddafrac::dda
