#pragma once
// The contact-free impact response compared (issue 6): the DDA twin against the FEM reference
// (impact_runs.hpp), gauge by gauge (impact_compare.hpp), checked against the scene's
// [verification] tolerances and reported.

#include "ddafrac/coupling/verification.hpp"
#include "ddafrac/coupling/verify.hpp"

namespace ddafrac::coupling {

/// The whole comparison of `ddafrac verify` for an impact scene: the DDA twin (kn =
/// options.stiffness_ratio · E), the FEM reference and, to tell time-integration from spatial
/// error, the FEM with the DDA's Newmark (kDdaNewmarkBeta, kDdaNewmarkGamma) at the DDA's dt;
/// impact_gauges.csv, impact_gauge_errors.csv and comparison.json in options.out_dir; checks
/// arrival_time (the gauges whose arrival is checked, ImpactSettings::min_arrival_time) and
/// gauge_rms (every gauge) of the scene's [verification].
VerificationReport verify_dynamic(const scene::Scene& scene, const VerifyOptions& options);

}  // namespace ddafrac::coupling
