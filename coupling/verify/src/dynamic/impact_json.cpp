#include <nlohmann/json.hpp>

#include "comparison_json.hpp"
#include "dynamic/impact_report.hpp"

namespace ddafrac::coupling {

std::string impact_json(const ImpactResults& r, double young) {
  nlohmann::json gauges = nlohmann::json::array();
  for (std::size_t g = 0; g < r.errors.size(); ++g) {
    const auto& e = r.errors[g];
    gauges.push_back({{"gauge", e.gauge},
                      {"rms_over_peak_syy", e.syy.rms_over_peak},
                      {"rms_over_peak_s1", e.s1_rms_over_peak},
                      {"peak_error", e.peak_error},
                      {"fem_peak_syy", e.syy.reference_peak.value},
                      {"dda_peak_syy", e.syy.approximation_peak.value},
                      {"fem_arrival", e.syy.reference_arrival},
                      {"dda_arrival", e.syy.approximation_arrival},
                      {"arrival_error", e.arrival_error},
                      {"arrival_checked", e.arrival_checked},
                      {"fem_half_one_rms_over_peak_syy", r.time_errors[g].syy.rms_over_peak}});
  }
  nlohmann::json j =
      comparison_json({"impact", r.dda.blocks, r.dda.steps, r.dda.wall, r.fem.wall, r.fem.dofs, r.dda.kn / young});
  j["dt"] = r.dda.dt;
  j["cg_total"] = r.dda.cg_total;
  j["dt_cuts"] = r.dda.dt_cuts;
  j["mean_rms_over_peak"] = r.summary.mean_rms;
  j["max_rms_over_peak"] = r.summary.max_rms;
  j["max_abs_arrival_error"] = r.summary.max_abs_arrival;
  j["mean_abs_peak_error"] = r.summary.mean_abs_peak;
  j["gauges"] = gauges;
  return j.dump(2) + "\n";
}

}  // namespace ddafrac::coupling
