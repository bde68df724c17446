#include "ddafrac/coupling/impact_compare.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ddafrac::coupling {

// Unqualified below: the parameter `reference` hides the namespace's name.
using reference::arrival_time;
using reference::compare_histories;
using reference::History;
using reference::peak_of;

std::vector<GaugeError> compare_gauges(const GaugeHistories& model, const GaugeHistories& reference,
                                       const ImpactSettings& settings) {
  if (model.names != reference.names) throw std::invalid_argument("compare_gauges: the two runs have different gauges");
  std::vector<GaugeError> out;
  for (std::size_t g = 0; g < model.names.size(); ++g) {
    GaugeError e;
    e.gauge = model.names[g];
    e.syy = compare_histories(model.syy[g], reference.syy[g], 1.0);
    // Arrival: both histories against the same absolute level, a share of the plane-wave stress.
    const double level = settings.arrival_fraction * reference.plane_wave_stress;
    const auto arrival = [level](const History& h) {
      const double peak = std::abs(peak_of(h).value);
      return peak > level ? arrival_time(h, level / peak) : h.t.back();
    };
    e.syy.reference_arrival = arrival(reference.syy[g]);
    e.syy.approximation_arrival = arrival(model.syy[g]);
    const double peak = std::abs(e.syy.reference_peak.value);
    e.peak_error = (std::abs(e.syy.approximation_peak.value) - peak) / peak;
    e.arrival_error = (e.syy.approximation_arrival - e.syy.reference_arrival) / e.syy.reference_arrival;
    e.arrival_checked = e.syy.reference_arrival >= settings.min_arrival_time && !reference.near_slot[g] &&
                        e.syy.reference_arrival >= kPhysicalArrivalShare * reference.earliest_arrival[g];
    e.s1_rms_over_peak = compare_histories(model.s1[g], reference.s1[g], settings.arrival_fraction).rms_over_peak;
    out.push_back(e);
  }
  return out;
}

ImpactErrorSummary summarise(std::vector<GaugeError> gauges) {
  ImpactErrorSummary s;
  s.gauges = std::move(gauges);
  for (const auto& g : s.gauges) {
    s.max_rms = std::max(s.max_rms, g.syy.rms_over_peak);
    s.mean_rms += g.syy.rms_over_peak;
    s.mean_abs_peak += std::abs(g.peak_error);
    s.max_abs_peak = std::max(s.max_abs_peak, std::abs(g.peak_error));
    if (g.arrival_checked) s.max_abs_arrival = std::max(s.max_abs_arrival, std::abs(g.arrival_error));
  }
  if (!s.gauges.empty()) {
    s.mean_rms /= static_cast<double>(s.gauges.size());
    s.mean_abs_peak /= static_cast<double>(s.gauges.size());
  }
  return s;
}

}  // namespace ddafrac::coupling
