#pragma once
// Shared by `ddafrac verify` and `ddafrac study convergence`: one comparison of a scene, written
// out as verification.md, summary.json and the plots in options.out_dir.

#include "ddafrac/coupling/verify.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::app {

/// Runs coupling::verify_scene and writes its files. A scene without the tolerances it needs
/// is refused with a CommandFailed naming the file and the missing verification.<key>s.
coupling::VerificationReport verify_and_report(const scene::Scene& scene, const coupling::VerifyOptions& options);

}  // namespace ddafrac::app
