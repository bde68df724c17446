#pragma once
// The impact comparison proper: per gauge, the σyy history of a model against the reference's
// (RMS error over the reference peak, peaks, P-wave arrivals), and the summary the penalty and
// convergence studies tabulate.

#include <string>
#include <vector>

#include "ddafrac/coupling/impact_runs.hpp"
#include "ddafrac/reference/compare.hpp"

namespace ddafrac::coupling {

/// A reference arrival earlier than this share of (distance from the patch) / c_p is a numerical
/// precursor of the FEM (P2 with consistent mass sends its short waves ahead of the front), not
/// the wave: such a gauge is not checked. 10% leaves room for the front smeared over an element.
inline constexpr double kPhysicalArrivalShare = 0.9;

/// Per gauge, σyy of a model against the reference.
struct GaugeError {
  std::string gauge;
  reference::HistoryComparison syy;  // RMS/peak, peaks, arrivals
  double peak_error = 0.0;           // (|peak| − |peak_ref|) / |peak_ref|: negative = the model's peak is smaller
  double arrival_error = 0.0;        // (t − t_ref) / t_ref, signed
  bool arrival_checked = false;      // reference arrival >= min_arrival_time, not beside the slot
  double s1_rms_over_peak = 0.0;     // RMS(σ1 − σ1_ref) / max |σ1_ref|
};

std::vector<GaugeError> compare_gauges(const GaugeHistories& model, const GaugeHistories& reference,
                                       const ImpactSettings& settings);

/// One DDA run against a reference: the numbers the penalty and convergence studies tabulate.
struct ImpactErrorSummary {
  std::vector<GaugeError> gauges;
  double max_rms = 0.0, mean_rms = 0.0;            // over all gauges
  double max_abs_arrival = 0.0;                    // over the checked gauges
  double mean_abs_peak = 0.0, max_abs_peak = 0.0;  // |peak_error| over all gauges
};
ImpactErrorSummary summarise(std::vector<GaugeError> gauges);

}  // namespace ddafrac::coupling
