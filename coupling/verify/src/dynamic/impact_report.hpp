#pragma once
// The impact comparison's report writers: its section of verification.md, comparison.json (the
// numbers `ddafrac study convergence` reads) and the CSV files (impact_gauges.csv: the three
// runs' histories, which the plots draw; impact_gauge_errors.csv: one row per gauge).

#include <filesystem>
#include <string>
#include <vector>

#include "ddafrac/coupling/impact_compare.hpp"
#include "ddafrac/coupling/impact_runs.hpp"
#include "ddafrac/fem/elasticity.hpp"
#include "ddafrac/scene/scene.hpp"

namespace ddafrac::coupling {

/// Everything one impact comparison produced.
struct ImpactResults {
  ImpactSettings settings;
  GaugeHistories dda, fem;
  GaugeHistories fem_dda_scheme;        // the FEM with the DDA's Newmark at the DDA's dt
  std::vector<GaugeError> errors;       // DDA against the FEM reference
  std::vector<GaugeError> time_errors;  // the FEM with the DDA's scheme against the reference
  ImpactErrorSummary summary;           // of `errors`
};

std::string impact_title();

/// A Newmark parameter as it is written: ¼, ½, ¾ as fractions ("1/4", ... with `ascii`), any
/// other value as a number.
std::string newmark_number(double value, bool ascii = false);

/// The section of verification.md. `material` is the disc's.
std::string impact_markdown(const scene::Scene& scene, const ImpactResults& results, const fem::Material& material);

/// comparison.json.
std::string impact_json(const ImpactResults& results, double young);

/// impact_gauges.csv and impact_gauge_errors.csv in `dir`.
void write_impact_csv(const std::filesystem::path& dir, const scene::Scene& scene, const ImpactResults& results);

}  // namespace ddafrac::coupling
