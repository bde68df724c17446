#include "dynamic/impact_checks.hpp"

#include <fmt/core.h>

#include <cmath>

namespace ddafrac::coupling {

std::vector<Check> impact_checks(const std::vector<GaugeError>& errors, const scene::Verification& tolerances) {
  std::vector<Check> checks;
  for (const auto& e : errors) {
    if (tolerances.arrival_time && e.arrival_checked)
      checks.push_back({fmt::format("P-wave arrival at gauge {}, DDA vs FEM", e.gauge), "arrival_time",
                        std::abs(e.arrival_error), *tolerances.arrival_time});
    if (tolerances.gauge_rms)
      checks.push_back({fmt::format("σyy history at gauge {}: RMS error / |FEM peak|", e.gauge), "gauge_rms",
                        e.syy.rms_over_peak, *tolerances.gauge_rms});
  }
  return checks;
}

}  // namespace ddafrac::coupling
