#pragma once
// Error measures of one model against a reference: fields sampled at the same points, and
// stress histories at gauges. Plain arrays in, numbers out; no model types. Part of the leaf
// library ddafrac::reference (with the closed forms of analytic.hpp).

#include <cstddef>
#include <vector>

namespace ddafrac::reference {

/// sqrt(Σ(a−r)² / Σr²) over paired samples; throws std::invalid_argument on a size mismatch
/// or an all-zero reference.
double relative_l2_error(const std::vector<double>& approximation, const std::vector<double>& reference);

/// A sampled history v(t), t strictly increasing.
struct History {
  std::vector<double> t;  // s
  std::vector<double> v;
};

/// Linear interpolation of h at time t (clamped to the first/last sample).
double value_at(const History& h, double t);

struct Peak {
  double value = 0.0;  // the sample of largest magnitude (with its sign)
  double time = 0.0;   // s
};
Peak peak_of(const History& h);

/// First time |v| reaches `fraction` of the peak magnitude (linear interpolation between
/// samples): the arrival of a wave at a gauge. Returns the last time if it never does.
double arrival_time(const History& h, double fraction);

struct HistoryComparison {
  double rms_over_peak = 0.0;  // RMS of (approximation − reference) at the reference times, / |reference peak|
  Peak reference_peak, approximation_peak;
  double reference_arrival = 0.0, approximation_arrival = 0.0;  // s
};

/// Compares `approximation` with `reference` over the times both cover. `arrival_fraction` is
/// the share of each history's own peak that marks its arrival.
HistoryComparison compare_histories(const History& approximation, const History& reference, double arrival_fraction);

}  // namespace ddafrac::reference
