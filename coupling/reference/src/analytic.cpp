#include "ddafrac/reference/analytic.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>
#include "ddafrac/common/angles.hpp"

namespace ddafrac::reference {
namespace {

constexpr double pi = common::kPi;
// Series terms are summed until they fall below this fraction of the leading (n = 1) term.
constexpr double series_relative_cutoff = 1e-16;
// Points closer to the rim than this (relative to R) are evaluated just inside it.
constexpr double series_rim_clearance = 1e-6;

void check_half_angle(const HondrosLoad& load) {
  if (!(load.half_angle > 0.0 && load.half_angle < 0.5 * pi))
    throw std::invalid_argument("Hondros half-angle must lie in (0, pi/2)");
}

/// Gauss-Legendre nodes and weights on [-1, 1] (Newton on the Legendre recurrence).
void gauss_legendre(int n, std::vector<double>& nodes, std::vector<double>& weights) {
  nodes.assign(static_cast<std::size_t>(n), 0.0);
  weights.assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < (n + 1) / 2; ++i) {
    double z = std::cos(pi * (i + 0.75) / (n + 0.5));
    double dp = 1.0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int k = 2; k <= n; ++k) {
        const double p2 = ((2.0 * k - 1.0) * z * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      if (n == 1) p0 = 1.0;
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-16) break;
    }
    const auto lo = static_cast<std::size_t>(i);
    const auto hi = static_cast<std::size_t>(n - 1 - i);
    nodes[lo] = -z;
    nodes[hi] = z;
    weights[lo] = weights[hi] = 2.0 / ((1.0 - z * z) * dp * dp);
  }
}

/// Polar (r, theta measured from the +y loading axis) components to Cartesian.
Stress2 from_loading_polar(double s_r, double s_t, double t_rt, double theta) {
  const double s = std::sin(theta), c = std::cos(theta);
  return {s_r * s * s + s_t * c * c + 2.0 * t_rt * s * c, s_r * c * c + s_t * s * s - 2.0 * t_rt * s * c,
          (s_r - s_t) * s * c + t_rt * (c * c - s * s)};
}

}  // namespace

Principal principal(const Stress2& s) {
  const double centre = 0.5 * (s.xx + s.yy);
  const double radius = std::hypot(0.5 * (s.xx - s.yy), s.xy);
  return {centre + radius, centre - radius, 0.5 * std::atan2(2.0 * s.xy, s.xx - s.yy)};
}

Stress2 radial_rim_force_stress(const Disc& disc, double force, double angle, double x, double y) {
  const double r = disc.radius();
  const double nx = -std::cos(angle), ny = -std::sin(angle);  // inward normal at the force
  const double dx = x + r * nx, dy = y + r * ny;              // from the force point to (x, y)
  const double d2 = dx * dx + dy * dy;
  const double flamant = -2.0 * force / (pi * disc.thickness) * (dx * nx + dy * ny) / (d2 * d2);
  const double uniform = force / (pi * disc.diameter * disc.thickness);
  return {flamant * dx * dx + uniform, flamant * dy * dy + uniform, flamant * dx * dy};
}

Stress2 point_load_stress(const Disc& disc, double load, double x, double y) {
  const Stress2 top = radial_rim_force_stress(disc, load, 0.5 * pi, x, y);
  const Stress2 bottom = radial_rim_force_stress(disc, load, 1.5 * pi, x, y);
  return {top.xx + bottom.xx, top.yy + bottom.yy, top.xy + bottom.xy};
}

double HondrosLoad::pressure(const Disc& disc) const {
  return load / (2.0 * half_angle * disc.radius() * disc.thickness);
}

Stress2 hondros_loaded_diameter(const Disc& disc, const HondrosLoad& load, double y) {
  check_half_angle(load);
  const double a = load.half_angle;
  const double k = 2.0 * load.pressure(disc) / pi;
  const double q = (y / disc.radius()) * (y / disc.radius());
  const double ratio = (1.0 - q) * std::sin(2.0 * a) / (1.0 - 2.0 * q * std::cos(2.0 * a) + q * q);
  const double angle = std::atan((1.0 + q) / (1.0 - q) * std::tan(a));
  return {k * (ratio - angle), -k * (ratio + angle), 0.0};
}

Stress2 hondros_horizontal_diameter(const Disc& disc, const HondrosLoad& load, double x) {
  check_half_angle(load);
  const double a = load.half_angle;
  const double k = 2.0 * load.pressure(disc) / pi;
  const double q = (x / disc.radius()) * (x / disc.radius());
  const double ratio = (1.0 - q) * std::sin(2.0 * a) / (1.0 + 2.0 * q * std::cos(2.0 * a) + q * q);
  const double angle = std::atan((1.0 - q) / (1.0 + q) * std::tan(a));
  return {k * (ratio - angle), -k * (ratio + angle), 0.0};
}

Stress2 hondros_centre(const Disc& disc, const HondrosLoad& load) { return hondros_loaded_diameter(disc, load, 0.0); }

Stress2 hondros_series(const Disc& disc, const HondrosLoad& load, double x, double y) {
  check_half_angle(load);
  const double a = load.half_angle;
  const double k = 2.0 * load.pressure(disc) / pi;
  const double rho = std::min(std::hypot(x, y) / disc.radius(), 1.0 - series_rim_clearance);
  const double q = rho * rho;
  const double theta = std::atan2(x, y);  // from the +y axis
  double sum_r = 0.0, sum_t = 0.0, sum_rt = 0.0;
  double q_power = 1.0;  // rho^(2n-2)
  for (int n = 1;; ++n) {
    const double s = std::sin(2.0 * n * a) * q_power;
    const double c = std::cos(2.0 * n * theta), sn = std::sin(2.0 * n * theta);
    sum_r += (1.0 - (1.0 - 1.0 / n) * q) * s * c;
    sum_t += (1.0 - (1.0 + 1.0 / n) * q) * s * c;
    sum_rt += (1.0 - q) * s * sn;
    q_power *= q;
    if (q_power < series_relative_cutoff) break;
  }
  return from_loading_polar(-k * (a + sum_r), -k * (a - sum_t), k * sum_rt, theta);
}

Stress2 hondros_superposition(const Disc& disc, const HondrosLoad& load, double x, double y, int points_per_arc) {
  check_half_angle(load);
  std::vector<double> nodes, weights;
  gauss_legendre(points_per_arc, nodes, weights);
  const double line_force = load.pressure(disc) * disc.radius() * disc.thickness;  // N/rad
  Stress2 sum;
  for (const double centre : {0.5 * pi, 1.5 * pi}) {
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const double force = line_force * load.half_angle * weights[i];
      const Stress2 s = radial_rim_force_stress(disc, force, centre + load.half_angle * nodes[i], x, y);
      sum.xx += s.xx;
      sum.yy += s.yy;
      sum.xy += s.xy;
    }
  }
  return sum;
}

Stress2 flattened_disc_centre_arc_mapped(const Disc& disc, double load, double flat_angle) {
  const double a = 0.5 * flat_angle;
  // Hondros' nominal load P_H = 2 a R t p with p chosen so that 2 R t p sin(a) = load.
  const HondrosLoad arc{load * a / std::sin(a), a};
  return hondros_centre(disc, arc);
}

double p_wave_speed(const Elastic& m, PlaneModel plane) {
  const double nu = m.poisson;
  if (plane == PlaneModel::Stress) return std::sqrt(m.young / (m.density * (1.0 - nu * nu)));
  return std::sqrt(m.young * (1.0 - nu) / (m.density * (1.0 + nu) * (1.0 - 2.0 * nu)));
}

double s_wave_speed(const Elastic& m) { return std::sqrt(m.young / (2.0 * m.density * (1.0 + m.poisson))); }

double impact_plane_wave_stress(const Elastic& m, PlaneModel plane, double v0) {
  return -m.density * p_wave_speed(m, plane) * v0;
}

}  // namespace ddafrac::reference
