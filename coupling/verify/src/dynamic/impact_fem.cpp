// The FEM reference of the impact: the same slotted disc, its patch held from t = 0, moving at
// v0, integrated by Newmark (fem_beta, fem_gamma), sampled at the gauges.

#include <algorithm>
#include <chrono>

#include "ddafrac/common/stopwatch.hpp"
#include "ddafrac/coupling/impact_runs.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "ddafrac/fem/dynamic_problem.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "dynamic/impact_scene.hpp"

namespace ddafrac::coupling {

namespace {
using Clock = std::chrono::steady_clock;
using common::seconds_since;

/// s between FEM gauge samples (a point search each).
constexpr double kFemSampleInterval = 1e-7;
}  // namespace

GaugeHistories run_impact_fem(const scene::Scene& scene, const ImpactSettings& settings) {
  const auto& geometry = impact_geometry(scene);
  GaugeHistories out = gauge_histories_for(scene);
  const auto mesh_start = Clock::now();
  fem::DynamicProblem p;
  const double size =
      settings.fem_element_size > 0.0 ? settings.fem_element_size : geometry.diameter / kFemElementsPerDiameter;
  p.mesh = meshes::generate_fem_mesh(scene.geometry, size, meshes::FemCells::Triangles);
  out.mesh_wall = seconds_since(mesh_start);
  const auto start = Clock::now();
  p.material = disc_material(scene);
  p.discretisation = {settings.fem_degree, settings.fem_refine};
  p.newmark = {settings.fem_beta, settings.fem_gamma};
  p.v0 = impact_speed(scene);
  p.dt = settings.fem_dt > 0.0 ? settings.fem_dt : std::min(dda_dt_of(scene, settings), kFemDtCap);
  p.end_time = end_time_of(scene, settings);
  p.output_interval = std::max(p.dt, kFemSampleInterval);
  for (const auto& g : scene.gauges) p.gauges.push_back({g.name, g.position[0], g.position[1]});
  const fem::DynamicResult r = fem::run_dynamic(p);
  for (const auto& g : r.gauges) add_sample(out, g.gauge, g.t, g.sample.stress.yy, g.sample.s1);
  out.dofs = r.stats.dofs;
  out.fem_solver = r.stats.solver;
  out.steps = r.steps;
  out.dt = p.dt;
  out.wall = seconds_since(start);
  return out;
}

}  // namespace ddafrac::coupling
