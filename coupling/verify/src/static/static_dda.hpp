#pragma once
// The static DDA twin run: the disc alone, its virtual joints bonded (dda_twin.hpp), static mode,
// the scene's pressure as consistent nodal forces on the rim vertices, and four anchors that
// resist rigid-body motion only, stepped until a step changes nothing that matters.

#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "ddafrac/coupling/verify.hpp"
#include "ddafrac/dda/engine.hpp"
#include "ddafrac/reference/analytic.hpp"
#include "static/static_setup.hpp"

namespace ddafrac::coupling {

/// Static twin's time step, s: static mode drops the velocities every step, and with this step
/// the inertia term 2M/dt² is ~1e-6 of the stiffness.
inline constexpr double kStaticTwinDt = 1e-2;
/// Static twin's allowed step displacement over P/E (m), the scale of the disc's elastic
/// deformation under the load P: the first step may take all of it.
inline constexpr double kStaticAllowedDisplacementOverPE = 10.0;
/// Static twin's contact search distance / allowed step displacement: its blocks move by the
/// elastic deformation only.
inline constexpr double kStaticTwinSearchDistanceFactor = 0.25;
/// Anchor stiffness k = this · E (N/m): stiff enough against the rotation that the two dead
/// loads drive (their couple P·D·θ; four anchors at R/2 resist with k·R² per radian).
inline constexpr double kAnchorStiffnessOverYoung = 0.05;
/// Anchors at this share of R from the centre, on both axes.
inline constexpr double kAnchorRadiusShare = 0.5;
/// A static state: the last step's largest displacement / the largest total displacement
/// below this.
inline constexpr double kStaticTolerance = 1e-7;
/// Steps when VerifyOptions::max_steps gives none.
inline constexpr int kStaticDefaultMaxSteps = 40;

/// One block of the twin: undeformed centroid and area, and its stress at the end of the run.
struct BlockStress {
  double x = 0.0, y = 0.0;    // m
  double area = 0.0;          // m²
  reference::Stress2 stress;  // Pa
};

struct StaticDdaRun {
  std::vector<BlockStress> blocks;
  long steps = 0;
  long dt_cuts = 0;
  double dt = 0.0;                      // s, the twin's time step
  double wall = 0.0, mesh_wall = 0.0;   // s
  double last_step_ratio = 0.0;         // last step's largest displacement / largest total displacement
  double last_stress_change = 0.0;      // max |Δσ| over the last step / the pressure
  std::vector<double> step_ratios;      // per step: largest step displacement / largest total displacement
  double max_total_displacement = 0.0;  // m
  std::size_t anchors = 0;
  double anchor_rigid = 0.0;       // largest rigid-body displacement the anchors resisted, m
  double anchor_force = 0.0;       // largest anchor spring force, N/m
  std::size_t loads = 0;           // point loads
  double applied_resultant = 0.0;  // |Σ f| of the point loads, N/m
  double applied_top = 0.0;        // vertical resultant on the upper half, N/m
  double kn = 0.0;                 // N/m, of the bonded joints
  double ks_over_kn = 0.0;         // of the bonded joints
  double mean_block_size = 0.0;    // m, sqrt(disc area / blocks)
  std::string solver;
  std::unique_ptr<dda::Engine> engine;  // the final state: profiles sample its deformed blocks
};

StaticDdaRun run_static_dda(const scene::Scene& scene, const StaticSetup& setup, const VerifyOptions& options);

}  // namespace ddafrac::coupling
