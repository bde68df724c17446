#pragma once
// The stability study (issue 6): the DDA engine on stiff and extreme cases —
// contact stiffness up to kn/E = 1e4, dt_max from 1e-9 s to 1e-5 s, impacts up to 50 m/s,
// sliver triangles, a 100× stiffer platen, static and dynamic modes — and one case that cannot
// run at all. For each case: no NaN, energy bounded, penetration against its allowance, dt cuts
// by reason, open–close failures, wall time and a verdict. No deal.II: builds without the FEM.
//
// Energy bound (stated once, used by the study and its test), from the engine's energy ledger
// (dda/energy_ledger.hpp): with E(t) the stored energy (kinetic + strain + contact springs +
// anchor springs) and S(t) = E(0) + the work of gravity, point loads and moving supports so far,
// a run that creates no energy keeps E(t) ≤ S(t): the DDA scheme (Newmark γ = 1, β = ½) only
// removes energy. The case passes if E(t) ≤ kEnergyBoundFactor · S(t) at every accepted step;
// the 0.5% margin covers what the linearised step cannot see (gaps and areas recomputed on the
// moved geometry), which the ledger's balance error measures (the table shows its largest value).

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "ddafrac/meshes/mesh.hpp"

namespace ddafrac::coupling {

/// E(t) ≤ kEnergyBoundFactor · S(t) at every step (see above).
constexpr double kEnergyBoundFactor = 1.005;

/// Allowed penetration = this × the mean over the triangulated blocks of each block's smallest
/// altitude (2·area / longest edge): deeper than that, a vertex may be judged against the wrong
/// edge and the contact geometry stops meaning anything.
constexpr double kPenetrationAllowanceFactor = 0.1;

/// A slab of sliver triangles (body "disc") resting on a plate (body "plate"): columns × rows
/// rectangles of (width/columns) × (height/rows), each cut along a diagonal. The slab's bottom edge
/// touches the plate's top edge at y = 0; the slab is centred on x = 0.
struct SliverSlab {
  double width = 0.1, height = 0.02;               // m
  int columns = 6, rows = 30;                      // 16.7 mm × 0.67 mm cells: aspect ratio 25
  double plate_width = 0.12, plate_height = 0.02;  // m
};
meshes::Mesh make_sliver_slab_mesh(const SliverSlab& slab);

/// Largest aspect ratio (longest edge / altitude onto it = longest edge² / (2·area)) of the
/// triangles of the named body; an equilateral triangle has 2/√3 ≈ 1.15.
double max_aspect_ratio(const meshes::Mesh& mesh, const std::string& body = "disc");

enum class Expectation { Stable, FailsCleanly };

enum class Verdict {
  Stable,           // end time reached, no NaN, energy within the bound, penetration within allowance
  PenetrationHigh,  // as Stable, but the deepest penetration exceeds the allowance
  FailedCleanly,    // the engine stopped with NumericalTrouble (exit status 3) and a message
  Unstable,         // NaN (not reported by the engine) or energy above the bound
  DidNotFinish,     // the case's step or wall-time guard stopped it before its end time
  Error             // anything else (scene, mesh, unexpected exception)
};
const char* to_string(Verdict v);

struct StabilityCase {
  std::string name;                    // e.g. "kn-1e4E-dynamic"
  std::string extreme;                 // what is extreme about it, for the table
  std::filesystem::path scene;         // relative to the scenes directory
  std::vector<std::string> overrides;  // --set style, applied before validation
  std::optional<SliverSlab> sliver;    // mesh built in code instead of the scene's generator
  double end_time = 0.0;               // s (replaces analysis.end_time)
  long max_steps = 0;                  // guard: stop after this many steps
  double max_wall = 120.0;             // guard: stop after this many wall seconds (checked per step)
  Expectation expect = Expectation::Stable;
  std::vector<std::string> expected_message;  // FailsCleanly: substrings the message must hold
};

/// The study's cases, in table order, reduced so that all of them take a few minutes on one
/// thread: impact discs of 800 blocks (case 4 geometry, the smallest its slot allows), flattened
/// discs of 400 blocks with their two platens, a slab of 360 sliver triangles; end times of 2 µs
/// to 2 ms. The last one is the deliberately impossible case.
std::vector<StabilityCase> stability_cases();

struct StabilityResult {
  std::string name, extreme, mode;  // mode: "static" or "dynamic"
  std::size_t blocks = 0;           // all blocks (disc triangles + platens/plate)
  double aspect = 0.0;              // largest triangle aspect ratio of the disc body
  long steps = 0;
  double time = 0.0, end_time = 0.0;  // s
  bool end_reached = false;
  bool nan = false;
  double energy_max = 0.0;           // J/m, largest E(t)
  double energy_ratio = 0.0;         // max over steps of E(t) / S(t)
  long energy_ratio_step = 0;        // where that maximum was
  double supplied_max = 0.0;         // J/m, largest S(t)
  double balance_error = 0.0;        // largest |balance error| of the energy ledger
  double penetration_max = 0.0;      // m
  double penetration_allowed = 0.0;  // m
  long cuts_displacement = 0, cuts_open_close = 0, cuts_solver = 0;
  double dt_min = 0.0, dt_max = 0.0;  // s, accepted steps
  long cracks = 0;
  long missed_contacts = 0;     // came in deep (dda::Statistics::missed_contacts)
  double deepest_missed = 0.0;  // m
  double wall = 0.0;            // s, meshing included
  int exit_status = 0;          // as `ddafrac run`: 0 completed, 3 numerical trouble (1 other errors)
  std::string message;          // engine message on trouble, guard or error description
  Verdict verdict = Verdict::Error;
  std::string verdict_text;  // verdict with its reason
  bool as_expected = false;  // Stable: verdict Stable or PenetrationHigh (an accuracy warning);
                             // FailsCleanly: FailedCleanly with every expected message part
};

struct StabilityProgress {
  long step = 0;
  double time = 0.0, end_time = 0.0, wall = 0.0;
};

/// Runs one case (on the caller's OpenMP thread count; results do not depend on it).
/// `progress` (optional) is called every `progress_every` wall seconds.
StabilityResult run_stability_case(const StabilityCase& c, const std::filesystem::path& scenes_dir,
                                   const std::function<void(const StabilityProgress&)>& progress = {},
                                   double progress_every = 10.0);

/// stability.csv: one row per case, every field of StabilityResult.
std::string stability_csv(const std::vector<StabilityResult>& results);
/// stability.md: the table of docs/results/stability.md (and the stated bounds above it).
std::string stability_markdown(const std::vector<StabilityResult>& results);

}  // namespace ddafrac::coupling
