// The static Brazilian disc three ways, phase by phase: the DDA twin and the FEM under the same
// load (static_dda, static_fem), compared at the DDA's block centroids (static_compare), checked
// against the scene's tolerances (static_checks), and reported (static_report).

#include "ddafrac/coupling/verify_static.hpp"

#include <fmt/core.h>

#include <stdexcept>

#include "ddafrac/common/whole_file.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "ddafrac/scene/scene.hpp"
#include "static/static_checks.hpp"
#include "static/static_report.hpp"

namespace ddafrac::coupling {

VerificationReport verify_static(const scene::Scene& scene, const VerifyOptions& options) {
  if (!scene.verification || !scene.verification->load)
    throw std::invalid_argument(fmt::format(
        "{}: verification.load is missing (the diametral load of the comparison, N/m)", scene.source.string()));
  const auto say = [&](const std::string& what) {
    if (!options.quiet) fmt::print("verify: {}\n", what);
  };
  StaticResults r;
  r.setup = static_setup(scene);
  say(fmt::format("DDA twin of {} ({} blocks target), static, P = {:.4g} N/m", scene.name, scene.mesh.target_blocks,
                  r.setup.load));
  r.dda = run_static_dda(scene, r.setup, options);
  say(fmt::format("DDA {} blocks, {} steps, {:.2f} s; FEM p = {}, {} refinement(s)", r.dda.blocks.size(), r.dda.steps,
                  r.dda.wall, options.fem_degree, options.fem_refine));
  r.fem = run_static_fem(scene, r.setup, options);
  say(fmt::format("FEM {} dofs, {:.2f} s", r.fem.dofs, r.fem.wall));
  r.comparison = compare_static(r.setup, r.dda, r.fem);
  if (r.dda.last_step_ratio >= kStaticTolerance)
    say(fmt::format("warning: the DDA did not reach a static state within {} steps", r.dda.steps));

  VerificationReport report;
  report.title = static_title(r.setup);
  report.dda_wall = r.dda.wall;
  report.fem_wall = r.fem.wall;
  report.checks = static_checks(r.setup, r.comparison, *scene.verification);
  const fem::Material material = disc_material(scene);
  report.markdown = static_markdown(r, material, options);
  write_static_csv(options.out_dir, r.comparison);
  common::write_whole_text(options.out_dir / "comparison.json", static_json(r, material.elastic.young));
  return report;
}

}  // namespace ddafrac::coupling
