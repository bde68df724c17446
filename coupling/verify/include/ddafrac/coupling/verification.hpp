#pragma once
// What one comparison of `ddafrac verify` reports: numbers checked against the
// tolerances of the scene's [verification] table, and a section of verification.md. Shared by
// the static (Brazilian disc) and the dynamic (contact-free impact) comparisons.

#include <algorithm>
#include <string>
#include <vector>

namespace ddafrac::coupling {

/// One measured error against its tolerance (both relative, dimensionless).
struct Check {
  std::string what;        // e.g. "centre sxx, DDA vs FEM"
  std::string key;         // the [verification] key that sets the tolerance, e.g. "centre_stress"
  double value = 0.0;      // measured relative error
  double tolerance = 0.0;  // from the scene
  bool passed() const { return value <= tolerance; }
};

struct VerificationReport {
  std::string title;     // e.g. "Static Brazilian disc: DDA vs FEM vs Hondros"
  std::string markdown;  // section for verification.md: settings, run times, error tables, plots
  std::vector<Check> checks;
  double dda_wall = 0.0;  // s
  double fem_wall = 0.0;  // s
  /// Passed when there is at least one check and every check passes.
  bool passed() const {
    return !checks.empty() && std::all_of(checks.begin(), checks.end(), [](const Check& c) { return c.passed(); });
  }
};

}  // namespace ddafrac::coupling
