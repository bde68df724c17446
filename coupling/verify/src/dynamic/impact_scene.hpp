#pragma once
// What the impact comparison reads from the scene, and the gauges both models sample.

#include <cstddef>

#include "ddafrac/coupling/impact_runs.hpp"
#include "ddafrac/meshes/geometry.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

/// Throws std::runtime_error naming the file when the scene is not an impact disc.
const meshes::ImpactDisc& impact_geometry(const scene::Scene& scene);

/// |v0| of the disc, m/s.
double impact_speed(const scene::Scene& scene);

/// The settings' end time and DDA time step, or the scene's where the settings give none, s.
double end_time_of(const scene::Scene& scene, const ImpactSettings& settings);
double dda_dt_of(const scene::Scene& scene, const ImpactSettings& settings);

/// Empty histories for the scene's gauges, with what decides whether a gauge's arrival is
/// checked: the plane-wave stress, which gauges lie beside the slot, the earliest physical
/// arrival at each.
GaugeHistories gauge_histories_for(const scene::Scene& scene);

void add_sample(GaugeHistories& h, std::size_t gauge, double t, double syy, double s1);

}  // namespace ddafrac::coupling
