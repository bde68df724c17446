#include <fmt/core.h>

#include <cmath>
#include <sstream>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/coupling/scene_fem.hpp"
#include "dynamic/impact_report.hpp"
#include "dynamic/impact_scene.hpp"

namespace ddafrac::coupling {

using common::kPi;

namespace {

constexpr double kMPa = 1e-6;  // MPa per Pa

std::string format_mpa(double pa) { return fmt::format("{:.2f}", pa * kMPa); }
std::string format_us(double s) { return fmt::format("{:.2f}", s * 1e6); }
std::string format_percent(double r) { return fmt::format("{:+.1f}%", 100.0 * r); }

/// "(β, γ)" of a Newmark scheme; `separator` between the two.
std::string newmark(double beta, double gamma, const char* separator = ", ") {
  return "(" + newmark_number(beta) + separator + newmark_number(gamma) + ")";
}

void scene_paragraph(std::ostream& md, const scene::Scene& scene, const ImpactResults& r,
                     const fem::Material& material) {
  const auto& geometry = impact_geometry(scene);
  const reference::Elastic& m = material.elastic;
  const reference::PlaneModel plane = material.plane;
  md << fmt::format(
      "Scene `{}`: impact disc D = {:.0f} mm with its joint slot (θ = {:.0f}°, γ = {:.2f}, width {:.1f} mm, open and "
      "traction-free in both models), v0 = {:.2f} m/s, impact patch of half-angle {:.1f}° held from t = 0, no "
      "gravity, {:.0f} µs. E = {:.4g} GPa, ν = {}, ρ = {:.0f} kg/m³, c_p = {:.1f} m/s ({}), plane-wave stress "
      "−ρ c_p v0 = {:.2f} MPa.\n\n",
      scene.name, geometry.diameter * 1e3, geometry.joint_angle * 180.0 / kPi, geometry.connectivity,
      geometry.joint_width * 1e3, impact_speed(scene), geometry.patch_half_angle * 180.0 / kPi,
      end_time_of(scene, r.settings) * 1e6, m.young * 1e-9, m.poisson, m.density, reference::p_wave_speed(m, plane),
      plane == reference::PlaneModel::Stress ? "plane stress" : "plane strain",
      reference::impact_plane_wave_stress(m, plane, impact_speed(scene)) * kMPa);
}

void models_table(std::ostream& md, const ImpactResults& r, double young) {
  const ImpactSettings& settings = r.settings;
  const GaugeHistories& dda = r.dda;
  const GaugeHistories& fem = r.fem;
  md << "| model | settings | run time (s) |\n|---|---|---|\n";
  md << fmt::format(
      "| DDA twin | {} blocks, {} bonded unbreakable virtual joints, kn = {:.4g} N/m (kn/E = {:.4g}), patch vertices "
      "held by fixed points of {:.0f} E, dt = {:.3g} s, Newmark {}, {} steps, {} CG iterations (max {} per "
      "solve), {} dt cuts, {} thread(s) | {:.2f} (+ {:.2f} meshing) |\n",
      dda.blocks, dda.joints, dda.kn, dda.kn / young, settings.anchor_ratio, dda.dt,
      newmark(kDdaNewmarkBeta, kDdaNewmarkGamma), dda.steps, dda.cg_total, dda.cg_max, dda.dt_cuts, settings.threads,
      dda.wall, dda.mesh_wall);
  md << fmt::format(
      "| FEM reference | P{} triangles, {} refinement(s), element size D/{:.0f}, {} dofs, Newmark {}, dt = {:.3g} "
      "s, {} steps, {} | {:.2f} |\n",
      settings.fem_degree, settings.fem_refine, kFemElementsPerDiameter, fem.dofs,
      newmark(settings.fem_beta, settings.fem_gamma), fem.dt, fem.steps, fem.fem_solver, fem.wall);
  md << fmt::format("| FEM, DDA's scheme | as the reference but Newmark {} at dt = {:.3g} s | {:.2f} |\n\n",
                    newmark(kDdaNewmarkBeta, kDdaNewmarkGamma), r.fem_dda_scheme.dt, r.fem_dda_scheme.wall);
}

void compliance_paragraph(std::ostream& md, const ImpactResults& r, double young) {
  const double e_eff = effective_modulus_ratio(r.dda.kn / young);
  md << fmt::format(
      "Joint compliance: with 1/E_eff = 1/E + {:.2f}/kn the DDA's effective modulus is {:.4f} E, so its P wave is "
      "expected {:.1f}% slower (arrivals {:+.1f}%).\n\n",
      kJointCompliance, e_eff, 100.0 * (1.0 - std::sqrt(e_eff)), 100.0 * (1.0 / std::sqrt(e_eff) - 1.0));
}

void gauge_table(std::ostream& md, const scene::Scene& scene, const ImpactResults& r) {
  const ImpactSettings& settings = r.settings;
  const std::string dda_scheme = newmark(kDdaNewmarkBeta, kDdaNewmarkGamma);
  md << fmt::format(
      "σyy per gauge (arrival: first time |σyy| reaches {:.0f}% of ρ c_p v0; arrival checked where the "
      "FEM's arrival is ≥ {:.0f} µs and ≥ {:g} × (distance from the patch)/c_p, i.e. not a precursor of the FEM, and "
      "the "
      "gauge is more than one DDA block from the slot). The last column is the FEM with the DDA's Newmark {} at the "
      "DDA's dt "
      "against the reference: the time-integration share of the error.\n\n",
      100.0 * settings.arrival_fraction, settings.min_arrival_time * 1e6, kPhysicalArrivalShare, dda_scheme);
  md << fmt::format(
      "| gauge | x, y (mm) | FEM peak (MPa) at µs | DDA peak (MPa) at µs | peak error | FEM arrival (µs) | DDA "
      "arrival (µs) | arrival error | RMS/peak σyy | RMS/peak σ1 | FEM {} RMS/peak |\n"
      "|---|---|---|---|---|---|---|---|---|---|---|\n",
      newmark(kDdaNewmarkBeta, kDdaNewmarkGamma, ","));
  for (std::size_t g = 0; g < r.errors.size(); ++g) {
    const auto& e = r.errors[g];
    md << fmt::format(
        "| {} | {:.1f}, {:.1f} | {} at {} | {} at {} | {} | {} | {} | {}{} | {:.3f} | {:.3f} | {:.3f} |\n", e.gauge,
        scene.gauges[g].position[0] * 1e3, scene.gauges[g].position[1] * 1e3, format_mpa(e.syy.reference_peak.value),
        format_us(e.syy.reference_peak.time), format_mpa(e.syy.approximation_peak.value),
        format_us(e.syy.approximation_peak.time), format_percent(e.peak_error), format_us(e.syy.reference_arrival),
        format_us(e.syy.approximation_arrival), format_percent(e.arrival_error),
        e.arrival_checked ? "" : " (not checked)", e.syy.rms_over_peak, e.s1_rms_over_peak,
        r.time_errors[g].syy.rms_over_peak);
  }
}

void summary_and_files(std::ostream& md, const ImpactErrorSummary& summary) {
  md << fmt::format(
      "\nOver all gauges: RMS/peak σyy mean {:.3f}, max {:.3f}; |peak error| mean {:.1f}%, max {:.1f}%; largest "
      "checked |arrival error| {:.1f}%.\n\n",
      summary.mean_rms, summary.max_rms, 100.0 * summary.mean_abs_peak, 100.0 * summary.max_abs_peak,
      100.0 * summary.max_abs_arrival);
  md << "Files: `impact_gauges.csv` (t, model, gauge, σyy, σ1 of the three runs), `impact_gauge_errors.csv`, "
        "`comparison.json`.\n\n";
  md << "![σyy at the gauges, DDA twin vs FEM](impact_gauges_syy.png)\n\n";
  md << "![σ1 at the gauges, DDA twin vs FEM](impact_gauges_s1.png)\n\n";
}

}  // namespace

std::string impact_title() { return "Contact-free impact: DDA twin vs FEM gauge histories"; }

std::string newmark_number(double value, bool ascii) {
  if (value == 0.25) return ascii ? "1/4" : "¼";
  if (value == 0.5) return ascii ? "1/2" : "½";
  if (value == 0.75) return ascii ? "3/4" : "¾";
  return fmt::format("{:g}", value);
}

std::string impact_markdown(const scene::Scene& scene, const ImpactResults& r, const fem::Material& material) {
  std::ostringstream md;
  md << fmt::format("## {}\n\n", impact_title());
  scene_paragraph(md, scene, r, material);
  models_table(md, r, material.elastic.young);
  compliance_paragraph(md, r, material.elastic.young);
  gauge_table(md, scene, r);
  summary_and_files(md, r.summary);
  return md.str();
}

}  // namespace ddafrac::coupling
