// The contact-free impact compared, phase by phase: the DDA twin, the FEM reference and the FEM
// with the DDA's time scheme (impact_dda, impact_fem), gauge by gauge (impact_compare), checked
// against the scene's tolerances (impact_checks) and reported (impact_report).

#include "ddafrac/coupling/verify_dynamic.hpp"

#include <fmt/core.h>

#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "dynamic/impact_checks.hpp"
#include "dynamic/impact_report.hpp"
#include "dynamic/impact_scene.hpp"

namespace ddafrac::coupling {

namespace {

ImpactSettings settings_of(const VerifyOptions& options) {
  ImpactSettings settings;
  settings.stiffness_ratio = options.stiffness_ratio;
  settings.threads = options.threads;
  settings.max_steps = options.max_steps;
  settings.fem_degree = options.fem_degree;
  settings.fem_refine = options.fem_refine;
  settings.quiet = options.quiet;
  return settings;
}

/// The three runs: the DDA twin, the FEM reference, and the FEM with the DDA's Newmark at the
/// DDA's dt, whose distance from the reference is the part of the DDA's error that comes from
/// time integration alone.
void run_models(const scene::Scene& scene, bool quiet, ImpactResults& r) {
  const auto say = [quiet](const std::string& what) {
    if (!quiet) fmt::print("verify: {}\n", what);
  };
  const auto newmark = [](double beta, double gamma) {
    return newmark_number(beta, true) + ", " + newmark_number(gamma, true);
  };
  say("DDA twin (bonded, unbreakable virtual joints; impact patch held; no gravity)");
  r.dda = run_impact_dda(scene, r.settings);
  say(fmt::format("DDA {} blocks, {} steps, {:.1f} s; FEM reference (Newmark {})", r.dda.blocks, r.dda.steps,
                  r.dda.wall, newmark(r.settings.fem_beta, r.settings.fem_gamma)));
  r.fem = run_impact_fem(scene, r.settings);
  ImpactSettings dda_scheme = r.settings;
  dda_scheme.fem_beta = kDdaNewmarkBeta;
  dda_scheme.fem_gamma = kDdaNewmarkGamma;
  dda_scheme.fem_dt = r.dda.dt;
  say(fmt::format("FEM {} dofs, {:.1f} s; FEM with the DDA's Newmark ({}) at dt = {:.3g} s", r.fem.dofs, r.fem.wall,
                  newmark(kDdaNewmarkBeta, kDdaNewmarkGamma), r.dda.dt));
  r.fem_dda_scheme = run_impact_fem(scene, dda_scheme);
}

}  // namespace

VerificationReport verify_dynamic(const scene::Scene& scene, const VerifyOptions& options) {
  impact_geometry(scene);
  const fem::Material material = disc_material(scene);
  ImpactResults r;
  r.settings = settings_of(options);
  run_models(scene, options.quiet, r);
  r.errors = compare_gauges(r.dda, r.fem, r.settings);
  r.time_errors = compare_gauges(r.fem_dda_scheme, r.fem, r.settings);
  r.summary = summarise(r.errors);

  write_impact_csv(options.out_dir, scene, r);
  VerificationReport report;
  report.title = impact_title();
  report.dda_wall = r.dda.wall;
  report.fem_wall = r.fem.wall;
  if (scene.verification) report.checks = impact_checks(r.errors, *scene.verification);
  report.markdown = impact_markdown(scene, r, material);
  common::write_whole_text(options.out_dir / "comparison.json", impact_json(r, material.elastic.young));
  return report;
}

}  // namespace ddafrac::coupling
