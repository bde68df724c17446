#pragma once
// `ddafrac verify` (issue 6): the same scene run by the DDA (virtual joints bonded and
// unbreakable, the continuum's twin) and by the FEM reference (and the analytic solution where
// one exists), compared against the tolerances of the scene's [verification] table.
//
// verify_scene dispatches on the geometry: an impact disc goes to verify_dynamic (the
// contact-free elastic response, verify_dynamic.hpp), every other scene to verify_static (the
// Brazilian disc at one load level, verify_static.hpp).

#include <filesystem>
#include <string>
#include <vector>

#include "ddafrac/coupling/verification.hpp"

namespace ddafrac::scene {
struct Scene;
}

namespace ddafrac::coupling {

struct VerifyOptions {
  std::filesystem::path out_dir;  // CSV and PNG files of the comparison are written here
  int threads = 1;                // OpenMP threads of the DDA (results do not depend on it)
  int fem_degree = 2;             // polynomial degree of the FEM reference
  int fem_refine = 0;             // uniform refinements of the FEM mesh
  /// DDA contact stiffness kn of every joint set as a multiple of Young's modulus, each set
  /// keeping its ks/kn; <= 0 keeps the scene's values. The joints' compliance lowers the twin's
  /// effective modulus (effective_modulus_ratio, impact_runs.hpp).
  double stiffness_ratio = 100.0;
  int max_steps = 0;    // cap on DDA steps (0: the comparison's own default)
  bool figures = true;  // draw PNGs (matplotlib) into out_dir
  bool quiet = false;   // no progress lines on stdout
};

/// The scene's [verification] keys a comparison needs, as "verification.<key>" names, that
/// the scene does not set (empty: it can be verified).
std::vector<std::string> missing_tolerances(const scene::Scene& scene);

/// Runs the comparison that fits the scene (impact disc: dynamic; otherwise static).
/// Throws std::runtime_error for a scene it cannot compare (naming the file and what is missing).
VerificationReport verify_scene(const scene::Scene& scene, const VerifyOptions& options);

}  // namespace ddafrac::coupling
