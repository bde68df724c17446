#include "ddafrac/reference/compare.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ddafrac::reference {

namespace {
void require_history(const History& h) {
  if (h.t.empty() || h.t.size() != h.v.size())
    throw std::invalid_argument("a history needs as many values as times, and at least one");
}
}  // namespace

double relative_l2_error(const std::vector<double>& approximation, const std::vector<double>& reference) {
  if (approximation.size() != reference.size())
    throw std::invalid_argument("relative_l2_error: the two fields have different numbers of samples");
  double difference = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < reference.size(); ++i) {
    difference += (approximation[i] - reference[i]) * (approximation[i] - reference[i]);
    norm += reference[i] * reference[i];
  }
  if (!(norm > 0.0)) throw std::invalid_argument("relative_l2_error: the reference field is zero");
  return std::sqrt(difference / norm);
}

double value_at(const History& h, double t) {
  require_history(h);
  if (t <= h.t.front()) return h.v.front();
  if (t >= h.t.back()) return h.v.back();
  const auto upper = std::upper_bound(h.t.begin(), h.t.end(), t);
  const std::size_t i = static_cast<std::size_t>(upper - h.t.begin());
  const double w = (t - h.t[i - 1]) / (h.t[i] - h.t[i - 1]);
  return (1.0 - w) * h.v[i - 1] + w * h.v[i];
}

Peak peak_of(const History& h) {
  require_history(h);
  std::size_t best = 0;
  for (std::size_t i = 1; i < h.v.size(); ++i)
    if (std::abs(h.v[i]) > std::abs(h.v[best])) best = i;
  return {h.v[best], h.t[best]};
}

double arrival_time(const History& h, double fraction) {
  const double level = fraction * std::abs(peak_of(h).value);
  if (std::abs(h.v.front()) >= level) return h.t.front();
  for (std::size_t i = 1; i < h.v.size(); ++i) {
    const double a = std::abs(h.v[i - 1]), b = std::abs(h.v[i]);
    if (b >= level) return h.t[i - 1] + (level - a) / (b - a) * (h.t[i] - h.t[i - 1]);
  }
  return h.t.back();
}

HistoryComparison compare_histories(const History& approximation, const History& reference, double arrival_fraction) {
  require_history(approximation);
  require_history(reference);
  HistoryComparison out;
  out.reference_peak = peak_of(reference);
  out.approximation_peak = peak_of(approximation);
  out.reference_arrival = arrival_time(reference, arrival_fraction);
  out.approximation_arrival = arrival_time(approximation, arrival_fraction);
  const double begin = std::max(approximation.t.front(), reference.t.front());
  const double end = std::min(approximation.t.back(), reference.t.back());
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < reference.t.size(); ++i) {
    if (reference.t[i] < begin || reference.t[i] > end) continue;
    const double d = value_at(approximation, reference.t[i]) - reference.v[i];
    sum += d * d;
    ++count;
  }
  const double peak = std::abs(out.reference_peak.value);
  if (count == 0 || !(peak > 0.0))
    throw std::invalid_argument("compare_histories: no common times, or a zero reference");
  out.rms_over_peak = std::sqrt(sum / static_cast<double>(count)) / peak;
  return out;
}

}  // namespace ddafrac::reference
