#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "ddafrac/common/angles.hpp"
#include "static/static_report.hpp"

namespace ddafrac::coupling {

using common::kPi;

namespace {

/// Rows of the list of the worst blocks; the rest are in blocks.csv.
constexpr std::size_t kWorstRowsShown = 15;

std::string mpa(double v) { return fmt::format("{:.4f}", v / 1e6); }

void disc_and_models(std::ostream& md, const StaticResults& r, const fem::Material& mat, const VerifyOptions& options) {
  const StaticSetup& st = r.setup;
  const StaticDdaRun& dda = r.dda;
  const StaticFemRun& fem = r.fem;
  md << fmt::format("Disc D = {} mm, E = {:.4g} GPa, ν = {}, plane {}; ", st.diameter * 1e3, mat.elastic.young / 1e9,
                    mat.elastic.poisson, mat.plane == fem::PlaneModel::Stress ? "stress" : "strain");
  if (st.flattened)
    md << fmt::format(
        "flattened disc (flats of {:.1f}°), uniform pressure {:.4g} MPa on both flats (load P = {:.4g} N/m).\n\n",
        2 * st.half_angle * 180 / kPi, st.pressure / 1e6, st.load);
  else
    md << fmt::format(
        "Hondros arcs 2α = {:.1f}°, radial pressure p = {:.4g} MPa (nominal load P = 2αRp = {:.4g} N/m).{}\n\n",
        2 * st.half_angle * 180 / kPi, st.pressure / 1e6, st.load, st.slit ? " Central slit." : "");
  md << "### Models\n\n| | settings | run time (s) |\n|---|---|---|\n";
  md << fmt::format(
      "| DDA | {} blocks (mean size {:.2f} mm), virtual joints bonded and unbreakable (σt = c = ∞), kn = {:.3g} N/m "
      "= {:.0f}·E, ks = {:g}·kn; static mode (velocities reset every step), dt = {:.0e} s (inertia ≈ 0), {} solver; "
      "{} consistent nodal loads (resultant {:.2e} N/m; vertical load on the upper half {:.6g} N/m); {} anchors "
      "({:g}·E N/m) that follow the deformation and resist only rigid-body motion | {:.2f} (mesh {:.2f}) |\n",
      dda.blocks.size(), dda.mean_block_size * 1e3, dda.kn, dda.kn / mat.elastic.young, dda.ks_over_kn, dda.dt,
      dda.solver, dda.loads, dda.applied_resultant, dda.applied_top, dda.anchors, kAnchorStiffnessOverYoung, dda.wall,
      dda.mesh_wall);
  md << fmt::format(
      "| FEM | P{} triangles, element size {:.1f} mm, {} refinement(s): {} cells, {} dofs, CG+AMG {} iterations; load "
      "as a "
      "boundary pressure{} | {:.2f} |\n",
      options.fem_degree, fem.element_size * 1e3, options.fem_refine, fem.cells, fem.dofs, fem.iterations,
      st.flattened ? " on the top flat, bottom flat on rollers (u_y = 0)"
                   : " on the arcs (rigid modes pinned, no pin force)",
      fem.wall);
  if (st.flattened)
    md << "\nThe supports differ under the bottom flat: the FEM holds it on rollers (the reaction concentrates at the "
          "flat's "
          "edges), the DDA carries the same uniform pressure on both flats (no supports: a DDA anchor would hold both "
          "components). The centre and the field away from the bottom flat are unaffected; the blocks next to it are "
          "not.\n";
  if (st.analytic) md << "| analytic | Hondros (1959) Fourier series at every block centroid | – |\n";
  md << "\n";
}

void static_state(std::ostream& md, const StaticResults& r) {
  const StaticDdaRun& dda = r.dda;
  md << fmt::format(
      "How the DDA reached a static state: static mode (velocities reset every step, so the kinetic energy is zero by "
      "construction and the measure of equilibrium is what the last step still changed), {} steps (dt cuts: {}); the "
      "last step moved no vertex by more than {:.2e} "
      "of the largest total displacement ({:.3e} m) and changed no block stress by more than {:.2e} of the pressure. "
      "Largest "
      "anchor force {:.3g} N/m ({:.1e} of the load).\n\n",
      dda.steps, dda.dt_cuts, dda.last_step_ratio, dda.max_total_displacement, dda.last_stress_change, dda.anchor_force,
      dda.anchor_force / r.setup.load);
  md << "Largest step displacement / largest total displacement, step by step:";
  for (const double ratio : dda.step_ratios) md << fmt::format(" {:.1e}", ratio);
  md << ".\n\n";
  if (dda.last_step_ratio >= kStaticTolerance)
    md << fmt::format(
        "**Warning: the DDA did not reach a static state within {} steps** (last step / total displacement {:.2e}, "
        "wanted below {:.0e}); the comparison below is of an unconverged state.\n\n",
        dda.steps, dda.last_step_ratio, kStaticTolerance);
}

void centre_stresses(std::ostream& md, const StaticResults& r) {
  const StaticSetup& st = r.setup;
  const StaticComparison& c = r.comparison;
  md << fmt::format(
      "### Centre stresses (MPa)\n\nArea-weighted mean over the blocks with centroid within R/{:g} = {:.1f} mm of the "
      "centre, every source sampled at the same centroids.\n\n",
      1.0 / kCentreRegionShare, c.centre_radius * 1e3);
  md << "| | σxx | σyy | τxy |\n|---|---|---|---|\n";
  md << fmt::format("| DDA | {} | {} | {} |\n| FEM | {} | {} | {} |\n", mpa(c.centre_dda.xx), mpa(c.centre_dda.yy),
                    mpa(c.centre_dda.xy), mpa(c.centre_fem.xx), mpa(c.centre_fem.yy), mpa(c.centre_fem.xy));
  if (st.analytic) {
    md << fmt::format("| Hondros | {} | {} | {} |\n", mpa(c.centre_ana.xx), mpa(c.centre_ana.yy), mpa(c.centre_ana.xy));
    md << fmt::format("| Hondros at the centre point | {} | {} | 0 |\n", mpa(c.centre_point_ana.xx),
                      mpa(c.centre_point_ana.yy));
  } else if (st.flattened) {
    const auto arc = reference::flattened_disc_centre_arc_mapped({st.diameter, 1.0}, st.load, 2 * st.half_angle);
    md << fmt::format("| arc-mapped approximation at the centre (not checked) | {} | {} | 0 |\n", mpa(arc.xx),
                      mpa(arc.yy));
  }
  md << fmt::format("\nDDA vs FEM: σxx {:.2f}%, σyy {:.2f}%", 100 * c.centre_dda_fem.xx, 100 * c.centre_dda_fem.yy);
  if (st.analytic)
    md << fmt::format("; DDA vs Hondros: σxx {:.2f}%, σyy {:.2f}%; FEM vs Hondros: σxx {:.2f}%, σyy {:.2f}%",
                      100 * c.centre_dda_ana.xx, 100 * c.centre_dda_ana.yy, 100 * c.centre_fem_ana.xx,
                      100 * c.centre_fem_ana.yy);
  md << ".\n\n";
}

void field_errors(std::ostream& md, const StaticResults& r) {
  const StaticComparison& c = r.comparison;
  md << "### Field errors at the block centroids\n\nRelative L2, area-weighted, over every disc block";
  if (c.outside_fem) md << fmt::format(" ({} centroids outside the FEM mesh left out)", c.outside_fem);
  md << ".\n\n| | (σxx, σyy, τxy) | σxx | σyy | τxy |\n|---|---|---|---|---|\n";
  const auto row = [&md](const char* what, const FieldError& e) {
    md << fmt::format("| {} | {:.4f} | {:.4f} | {:.4f} | {:.4f} |\n", what, e.all, e.xx, e.yy, e.xy);
  };
  row("DDA vs FEM", c.dda_fem);
  row(fmt::format("DDA vs FEM, inner disc r < {:g} R (away from the loads)", kInnerDiscShare).c_str(), c.dda_fem_inner);
  if (r.setup.analytic) {
    row("DDA vs Hondros", c.dda_ana);
    md << fmt::format("| FEM vs Hondros (quality of the reference) | {:.5f} | {:.5f} | {:.5f} | {:.5f} |\n",
                      c.fem_ana.all, c.fem_ana.xx, c.fem_ana.yy, c.fem_ana.xy);
  }
}

void worst_blocks(std::ostream& md, const StaticResults& r) {
  const StaticComparison& c = r.comparison;
  md << fmt::format(
      "\n### The worst {}% of blocks (DDA vs FEM)\n\nPointwise error |σ_DDA − σ_FEM| (tensor norm) over the RMS FEM "
      "stress "
      "({:.3g} MPa). Where they are: ",
      kWorstPercent, c.fem_rms / 1e6);
  bool first = true;
  for (const auto& [where, n] : c.worst_where) {
    md << (first ? "" : ", ") << fmt::format("{} {}", n, where);
    first = false;
  }
  md << fmt::format(
      " (\"near\" = within {:g} mean block sizes, {:.1f} mm).\n\n| block | r/R | angle (°) | error | σxx DDA / FEM "
      "(MPa) | "
      "σyy DDA / FEM (MPa) | why |\n|---|---|---|---|---|---|---|\n",
      kNearBlockSizes, c.near_distance * 1e3);
  for (std::size_t k = 0; k < std::min(c.worst.size(), kWorstRowsShown); ++k) {
    const auto& w = c.worst[k];
    const auto& b = c.blocks[w.block];
    md << fmt::format("| {} | {:.3f} | {:.1f} | {:.3f} | {} / {} | {} / {} | {} |\n", w.block,
                      std::hypot(b.x, b.y) / r.setup.radius, std::atan2(b.y, b.x) * 180 / kPi, w.error, mpa(b.dda.xx),
                      mpa(b.fem.xx), mpa(b.dda.yy), mpa(b.fem.yy), w.where);
  }
  if (c.worst.size() > kWorstRowsShown)
    md << fmt::format("\n({} more in blocks.csv.)\n", c.worst.size() - kWorstRowsShown);
}

void profiles(std::ostream& md) {
  md << "\n### Profiles\n\n`profiles.csv` (DDA block stress, FEM and analytic at the same points along both "
        "diameters), "
        "`blocks.csv` (every block centroid, all sources).\n\n"
        "![sxx and syy along the loaded diameter](profile_loaded.png)\n\n"
        "![sxx and syy along the horizontal diameter](profile_horizontal.png)\n\n";
}

}  // namespace

std::string static_title(const StaticSetup& st) {
  return st.analytic ? "Static Brazilian disc: DDA vs FEM vs Hondros" : "Static Brazilian disc: DDA vs FEM";
}

std::string static_markdown(const StaticResults& r, const fem::Material& material, const VerifyOptions& options) {
  std::ostringstream md;
  md << "## " << static_title(r.setup) << "\n\n";
  disc_and_models(md, r, material, options);
  static_state(md, r);
  if (r.comparison.has_centre) centre_stresses(md, r);
  field_errors(md, r);
  worst_blocks(md, r);
  profiles(md);
  return md.str();
}

}  // namespace ddafrac::coupling
