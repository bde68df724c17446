#pragma once
// The static comparison's report writers: its section of verification.md, comparison.json (the
// numbers `ddafrac study convergence` and the tests read) and the CSV files of every sample
// (blocks.csv, profiles.csv; the plots are drawn from profiles.csv).

#include <filesystem>
#include <string>

#include "ddafrac/coupling/verify.hpp"
#include "ddafrac/fem/elasticity.hpp"
#include "static/static_compare.hpp"

namespace ddafrac::coupling {

/// Everything one static comparison produced, in the order it was made.
struct StaticResults {
  StaticSetup setup;
  StaticDdaRun dda;
  StaticFemRun fem;
  StaticComparison comparison;
};

std::string static_title(const StaticSetup& setup);

/// The section of verification.md: settings, how the DDA reached rest, centre stresses, field
/// errors, the worst blocks, the profiles. `material` is the disc's.
std::string static_markdown(const StaticResults& results, const fem::Material& material, const VerifyOptions& options);

/// comparison.json.
std::string static_json(const StaticResults& results, double young);

/// profiles.csv and blocks.csv in `dir`.
void write_static_csv(const std::filesystem::path& dir, const StaticComparison& comparison);

}  // namespace ddafrac::coupling
