#pragma once
// Point in polygon, once for the tree: the DDA's block lookup (gauges) and contact search, and
// the placing of the static comparison's anchors.

#include <cstddef>

namespace ddafrac::common {

/// Crossing-number test: is (px, py) inside the polygon of the n vertices (x[k], y[k]), convex
/// or concave, in either orientation? A point exactly on an edge counts as inside one of the two
/// polygons that share the edge and outside the other (half-open rule), so a point on a shared
/// edge of a mesh is found in exactly one cell.
inline bool inside_polygon(const double* x, const double* y, std::size_t n, double px, double py) {
  bool inside = false;
  for (std::size_t k = 0, m = n - 1; k < n; m = k++)
    if ((y[k] > py) != (y[m] > py) && px < (x[m] - x[k]) * (py - y[k]) / (y[m] - y[k]) + x[k]) inside = !inside;
  return inside;
}

}  // namespace ddafrac::common
