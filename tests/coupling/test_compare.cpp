// Error measures against signals whose answers are known in closed form.
#define BOOST_TEST_MODULE coupling_compare
#include <boost/test/unit_test.hpp>

#include <cmath>

#include "ddafrac/common/angles.hpp"
#include "ddafrac/reference/compare.hpp"

using namespace ddafrac::reference;

namespace {
constexpr double kPi = ddafrac::common::kPi;

/// A half-sine pulse of amplitude a and width w starting at t0, sampled every dt up to t_end.
History pulse(double a, double t0, double w, double dt, double t_end) {
  History h;
  for (double t = 0.0; t <= t_end + 1e-15; t += dt) {
    h.t.push_back(t);
    h.v.push_back(t >= t0 && t <= t0 + w ? a * std::sin(kPi * (t - t0) / w) : 0.0);
  }
  return h;
}
}  // namespace

BOOST_AUTO_TEST_CASE(relative_l2_of_a_scaled_field_is_the_scale_error) {
  const std::vector<double> reference{1.0, -2.0, 3.0, 0.5};
  std::vector<double> scaled;
  for (double r : reference) scaled.push_back(1.03 * r);
  BOOST_TEST(std::abs(relative_l2_error(scaled, reference) - 0.03) < 1e-14);
  BOOST_TEST(relative_l2_error(reference, reference) == 0.0);
  BOOST_CHECK_THROW(relative_l2_error({1.0}, reference), std::invalid_argument);
  BOOST_CHECK_THROW(relative_l2_error({0.0}, {0.0}), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(shifted_pulse_arrives_later_by_the_shift) {
  const double dt = 1e-8, shift = 3e-6;
  const History reference = pulse(-16e6, 5e-6, 10e-6, dt, 40e-6);
  const History late = pulse(-16e6, 5e-6 + shift, 10e-6, dt, 40e-6);
  const auto c = compare_histories(late, reference, 0.1);
  // Linear interpolation of a smooth pulse: arrival exact to a small share of a sample step.
  BOOST_TEST(std::abs((c.approximation_arrival - c.reference_arrival) - shift) < 0.1 * dt);
  BOOST_TEST(std::abs(c.reference_peak.value + 16e6) < 1.0);
  BOOST_TEST(std::abs(c.reference_peak.time - 10e-6) < dt);
  // On a shared sampling grid no interpolation happens: the RMS is the plain sum over samples.
  double sum = 0.0;
  for (std::size_t i = 0; i < reference.t.size(); ++i) sum += std::pow(late.v[i] - reference.v[i], 2);
  const double expected = std::sqrt(sum / static_cast<double>(reference.t.size())) / 16e6;
  BOOST_TEST(std::abs(c.rms_over_peak - expected) < 1e-12);
  BOOST_TEST(c.rms_over_peak > 0.1);
}

BOOST_AUTO_TEST_CASE(identical_histories_on_different_grids_agree) {
  // The same smooth signal sampled at two rates: interpolation error of a linear interpolant,
  // ≤ (Δt²/8)·max|f''| = (Δt²/8)·a(π/w)², relative to a.
  const double a = 5e6, w = 10e-6, coarse = 2e-7;
  const History reference = pulse(a, 2e-6, w, 1e-8, 30e-6);
  const History approximation = pulse(a, 2e-6, w, coarse, 30e-6);
  const auto c = compare_histories(approximation, reference, 0.05);
  const double bound = coarse * coarse / 8.0 * std::pow(kPi / w, 2);
  BOOST_TEST(c.rms_over_peak < bound);
  BOOST_TEST(std::abs(value_at(reference, 7e-6) - a) < 1e-9 * a);  // the pulse's crest
}
