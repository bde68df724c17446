// The DDA twin of the impact: the bonded twin (dda_twin.hpp) of the disc alone, dynamic, its
// impact-patch vertices held by fixed points from t = 0, sampled at the gauges every step.

#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <set>
#include <stdexcept>

#include "ddafrac/common/stopwatch.hpp"
#include "ddafrac/common/thread_scope.hpp"
#include "ddafrac/coupling/dda_twin.hpp"
#include "ddafrac/coupling/impact_runs.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "ddafrac/dda/drive.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/meshes/generate.hpp"
#include "dynamic/impact_scene.hpp"

namespace ddafrac::coupling {

namespace {

using Clock = std::chrono::steady_clock;
using common::seconds_since;

/// A progress line every this many steps (ImpactSettings::quiet off).
constexpr long kProgressEverySteps = 200;

/// The scene's DDA mesh without the plate: only the cells of the disc body.
meshes::Mesh disc_only(const meshes::Mesh& mesh, const std::string& disc) {
  meshes::Mesh out;
  out.nodes = mesh.nodes;
  out.body_names = mesh.body_names;
  out.boundary_edges = mesh.boundary_edges;
  out.boundary_names = mesh.boundary_names;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c) {
    if (mesh.body_names[mesh.cell_body[c]] != disc) continue;
    out.cell_nodes.insert(out.cell_nodes.end(), mesh.cell_begin(c), mesh.cell_begin(c) + mesh.cell_size(c));
    out.cell_offsets.push_back(static_cast<meshes::Index>(out.cell_nodes.size()));
    out.cell_body.push_back(mesh.cell_body[c]);
  }
  return out;
}

/// Fixed points at every block vertex on the impact patch (the FEM holds the same nodes).
std::vector<dda::Anchor> patch_anchors(const meshes::Mesh& mesh) {
  const auto group = std::find(mesh.boundary_names.begin(), mesh.boundary_names.end(), "impact_patch");
  if (group == mesh.boundary_names.end()) throw std::runtime_error("the DDA mesh has no impact_patch boundary group");
  const auto g = static_cast<meshes::Index>(group - mesh.boundary_names.begin());
  std::set<meshes::Index> nodes;
  for (const auto& e : mesh.boundary_edges)
    if (e.group == g) nodes.insert({e.a, e.b});
  std::vector<dda::Anchor> anchors;
  for (std::size_t c = 0; c < mesh.cell_count(); ++c)
    for (const meshes::Index* n = mesh.cell_begin(c); n != mesh.cell_begin(c) + mesh.cell_size(c); ++n)
      if (nodes.count(*n)) {
        dda::Anchor a;
        a.block = static_cast<dda::Index>(c);
        a.x = a.x_start = mesh.nodes[*n].x;
        a.y = a.y_start = mesh.nodes[*n].y;
        anchors.push_back(a);
      }
  return anchors;
}

/// σyy and σ1 of the block that holds each gauge.
void sample_gauges(const dda::Engine& engine, GaugeHistories& out) {
  const auto& gauge_blocks = engine.gauge_blocks();
  for (std::size_t g = 0; g < gauge_blocks.size(); ++g) {
    const auto& stress = engine.blocks().stress[static_cast<std::size_t>(gauge_blocks[g])];
    add_sample(out, g, engine.time(), stress[1], reference::principal({stress[0], stress[1], stress[2]}).s1);
  }
}

}  // namespace

GaugeHistories run_impact_dda(const scene::Scene& scene, const ImpactSettings& settings) {
  impact_geometry(scene);
  const double young = disc_material(scene).elastic.young;
  DdaTwin twin = bonded_dda_twin(scene, settings.stiffness_ratio);
  twin.scene.analysis.mode = scene::Mode::Dynamic;
  twin.scene.analysis.dt_max = dda_dt_of(scene, settings);
  twin.scene.analysis.end_time = end_time_of(scene, settings);

  GaugeHistories out = gauge_histories_for(scene);
  const auto mesh_start = Clock::now();
  const meshes::Mesh mesh = disc_only(meshes::generate_dda_mesh(scene.geometry, scene.mesh), disc_body(scene).name);
  out.mesh_wall = seconds_since(mesh_start);

  const common::ThreadScope threads(settings.threads);
  const auto start = Clock::now();
  dda::EngineOptions options;
  options.anchors = patch_anchors(mesh);
  options.anchor_penalty_factor = settings.anchor_ratio * young / twin.scene.analysis.penalty;
  dda::Engine engine(twin.scene, mesh, options);
  out.blocks = engine.blocks().block_count();
  out.joints = engine.blocks().joints.size();
  out.dt = twin.scene.analysis.dt_max;
  out.kn = twin.kn;
  sample_gauges(engine, out);
  dda::DriveHooks hooks;
  hooks.before_step = [&] {
    return settings.max_steps > 0 && out.steps >= settings.max_steps ? dda::Next::Stop : dda::Next::Continue;
  };
  hooks.after_step = [&](const dda::StepReport& r) {
    ++out.steps;
    sample_gauges(engine, out);
    if (!settings.quiet && out.steps % kProgressEverySteps == 0)
      fmt::print("  DDA step {} t = {:.2f} µs, CG {}\n", out.steps, engine.time() * 1e6, r.cg_iterations);
    return dda::Next::Continue;
  };
  dda::drive(engine, twin.scene.analysis.end_time, hooks);
  const auto& st = engine.statistics();
  out.cg_total = st.cg_total;
  out.cg_max = st.cg_max;
  out.open_close_total = st.open_close_total;
  out.dt_cuts = st.cuts_displacement + st.cuts_open_close + st.cuts_solver;
  out.wall = seconds_since(start);
  return out;
}

double effective_modulus_ratio(double kn_over_e) { return 1.0 / (1.0 + kJointCompliance / kn_over_e); }

}  // namespace ddafrac::coupling
