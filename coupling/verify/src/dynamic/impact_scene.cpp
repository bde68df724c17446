#include "dynamic/impact_scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <variant>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/coupling/dda_twin.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "ddafrac/reference/analytic.hpp"

namespace ddafrac::coupling {

using common::kPi;

namespace {
/// The impact patch is sampled at this many points on each side of its centre for a gauge's
/// distance from it.
constexpr int kPatchSamplesPerSide = 50;
}  // namespace

const meshes::ImpactDisc& impact_geometry(const scene::Scene& s) {
  const auto* g = std::get_if<meshes::ImpactDisc>(&s.geometry);
  if (!g) throw std::runtime_error(s.source.string() + ": the dynamic comparison needs an impact_disc geometry");
  return *g;
}

double impact_speed(const scene::Scene& s) {
  const auto& v = disc_body(s).initial_velocity;
  return std::hypot(v[0], v[1]);
}

double end_time_of(const scene::Scene& s, const ImpactSettings& settings) {
  return settings.end_time > 0.0 ? settings.end_time : s.analysis.end_time;
}

double dda_dt_of(const scene::Scene& s, const ImpactSettings& settings) {
  return settings.dda_dt > 0.0 ? settings.dda_dt : s.analysis.dt_max;
}

GaugeHistories gauge_histories_for(const scene::Scene& s) {
  GaugeHistories h;
  const fem::Material m = disc_material(s);
  h.plane_wave_stress = std::abs(reference::impact_plane_wave_stress(m.elastic, m.plane, impact_speed(s)));
  // A gauge closer to the joint slot than one DDA block (the mean edge of an equilateral
  // triangle of the disc's area / target blocks) reports a block average over a region where σyy
  // changes by its full size: its arrival is reported, not checked.
  const auto& geometry = impact_geometry(s);
  const double block_size = std::sqrt(4.0 * kPi * geometry.diameter * geometry.diameter / 4.0 /
                                      (std::sqrt(3.0) * std::max(1, s.mesh.target_blocks)));
  const double half_length = 0.5 * geometry.connectivity * geometry.diameter;
  const double cx = std::cos(geometry.joint_angle), cy = std::sin(geometry.joint_angle);
  // Earliest physical arrival: the straight-line distance from the impact patch over c_p.
  const double cp = reference::p_wave_speed(m.elastic, m.plane);
  const double radius = 0.5 * geometry.diameter;
  for (const auto& g : s.gauges) {
    double nearest = std::numeric_limits<double>::infinity();
    for (int k = -kPatchSamplesPerSide; k <= kPatchSamplesPerSide; ++k) {
      const double angle = -0.5 * kPi + geometry.patch_half_angle * k / static_cast<double>(kPatchSamplesPerSide);
      nearest = std::min(
          nearest, std::hypot(g.position[0] - radius * std::cos(angle), g.position[1] - radius * std::sin(angle)));
    }
    h.earliest_arrival.push_back(nearest / cp);
    h.names.push_back(g.name);
    const double along = std::clamp(g.position[0] * cx + g.position[1] * cy, -half_length, half_length);
    const double distance =
        std::hypot(g.position[0] - along * cx, g.position[1] - along * cy) - 0.5 * geometry.joint_width;
    h.near_slot.push_back(distance < block_size);
  }
  h.syy.resize(s.gauges.size());
  h.s1.resize(s.gauges.size());
  return h;
}

void add_sample(GaugeHistories& h, std::size_t g, double t, double syy, double s1) {
  h.syy[g].t.push_back(t);
  h.syy[g].v.push_back(syy);
  h.s1[g].t.push_back(t);
  h.s1[g].v.push_back(s1);
}

}  // namespace ddafrac::coupling
