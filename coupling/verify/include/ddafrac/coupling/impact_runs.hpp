#pragma once
// The two models of the contact-free impact: the DDA twin of the continuum (virtual joints
// bonded and unbreakable, no plate: the impact-patch vertices held by stiff fixed points from
// t = 0, the disc moving at v0, no gravity) and the deal.II FEM reference of the same disc (same
// slotted geometry, the patch held from t = 0), each giving σyy and σ1 histories at the scene's
// gauges.
//
// The FEM reference does not depend on the DDA's penalty or time step, so the studies compute
// it once (run_impact_fem) and compare many DDA runs (run_impact_dda) against it.

#include <cstddef>
#include <string>
#include <vector>

#include "ddafrac/reference/compare.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

/// The DDA's time scheme as a Newmark method (β, γ): run with these, the FEM shows the part of
/// the DDA's error that comes from time integration alone.
inline constexpr double kDdaNewmarkBeta = 0.5;
inline constexpr double kDdaNewmarkGamma = 1.0;

/// What the comparison runs. Zeros mean "the scene's value" or the documented default.
struct ImpactSettings {
  /// kn/E of every joint set (virtual joints and real joints alike; ks keeps the scene's ks/kn).
  /// <= 0 keeps the scene's stiffnesses.
  double stiffness_ratio = 100.0;
  double dda_dt = 0.0;    // s, DDA dt_max; 0 = analysis.dt_max
  double end_time = 0.0;  // s; 0 = analysis.end_time
  int threads = 1;        // DDA OpenMP threads (results do not depend on it)
  int max_steps = 0;      // cap on DDA steps (0: none)
  /// Stiffness of each fixed point holding an impact-patch vertex, as a multiple of E
  /// (N/m per unit thickness / Pa). Independent of kn so that the penalty study varies only
  /// the joints.
  double anchor_ratio = 1000.0;
  int fem_degree = 2;
  int fem_refine = 0;
  double fem_element_size = 0.0;            // m; 0 = D/kFemElementsPerDiameter (as `ddafrac fem`)
  double fem_dt = 0.0;                      // s; 0 = min(DDA dt, kFemDtCap)
  double fem_beta = 0.25, fem_gamma = 0.5;  // Newmark of the reference
  /// Arrival of the wave at a gauge: the first time |σyy| reaches this share of the plane-wave
  /// stress ρ c_p v0 (the same level in both models).
  double arrival_fraction = 0.1;
  /// Gauges whose reference arrival is earlier than this are left out of the arrival checks
  /// (too close to the patch: the block size, not the wave speed, sets their arrival), and so
  /// are gauges closer to the joint slot than one DDA block and gauges whose reference arrival
  /// is earlier than kPhysicalArrivalShare × (distance from the patch) / c_p (a numerical
  /// precursor of the FEM).
  double min_arrival_time = 5e-6;  // s
  bool quiet = true;               // progress lines on stdout
};

/// The FEM reference's time step is at most this, s (c_p dt = 0.06 mm << h = 4 mm).
inline constexpr double kFemDtCap = 2.5e-8;

/// Stress histories at the scene's gauges (σyy and σ1, Pa) and what the run cost.
struct GaugeHistories {
  std::vector<std::string> names;
  std::vector<reference::History> syy, s1;
  std::vector<bool> near_slot;           // per gauge: closer to the joint slot than one DDA block
  std::vector<double> earliest_arrival;  // per gauge, s: distance from the impact patch / c_p
  double plane_wave_stress = 0.0;        // Pa, |ρ c_p v0| of the scene: the scale of the arrival level
  double wall = 0.0;                     // s, meshing excluded
  double mesh_wall = 0.0;                // s
  // DDA only.
  std::size_t blocks = 0, joints = 0;
  long steps = 0, cg_total = 0, open_close_total = 0, dt_cuts = 0;
  int cg_max = 0;
  double dt = 0.0;  // s, dt_max used
  double kn = 0.0;  // N/m, joint normal stiffness used
  // FEM only.
  std::size_t dofs = 0;
  std::string fem_solver;  // the linear solver
};

/// The DDA twin (see the top of this file).
GaugeHistories run_impact_dda(const scene::Scene& scene, const ImpactSettings& settings);

/// The FEM reference with (fem_beta, fem_gamma) at fem_dt.
GaugeHistories run_impact_fem(const scene::Scene& scene, const ImpactSettings& settings);

/// α of 1/E_eff = 1/E + α/kn, the compliance of a bonded triangulation's joints, measured on a
/// glued bar (test dda_fracture).
inline constexpr double kJointCompliance = 1.35;

/// E_eff / E of a bonded triangulation whose joints have normal stiffness kn = kn_over_e · E
/// (kJointCompliance). The P wave is slower by sqrt(E_eff/E).
double effective_modulus_ratio(double kn_over_e);

}  // namespace ddafrac::coupling
