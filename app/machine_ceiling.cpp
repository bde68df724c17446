#include "machine_ceiling.hpp"

#include <omp.h>

#include <chrono>
#include <cstdint>
#include <vector>
#include "ddafrac/common/stopwatch.hpp"
#include "ddafrac/common/thread_scope.hpp"

namespace ddafrac::app {

namespace {

constexpr std::int64_t kChains = 64;              // independent FP chains, split over threads
constexpr std::int64_t kChainLength = 4'000'000;  // multiply-adds per chain
constexpr std::size_t kTriadLength = 16'000'000;  // doubles per array: 3 × 128 MB, beyond any cache
constexpr int kTriadRepeats = 8;

using common::seconds_since;

/// Dependent multiply-add chains: no memory traffic, one chain per loop iteration.
double compute_kernel_seconds(int threads, double& sink) {
  omp_set_num_threads(threads);
  const auto start = std::chrono::steady_clock::now();
  double total = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : total)
  for (std::int64_t c = 0; c < kChains; ++c) {
    double x = 1.0 + 1e-9 * static_cast<double>(c);
    for (std::int64_t k = 0; k < kChainLength; ++k) x = x * 0.999999999 + 1e-9;
    total += x;
  }
  sink += total;
  return seconds_since(start);
}

/// a = b + s·c over arrays far larger than the caches (first touch by the same threads).
double memory_kernel_seconds(int threads, std::vector<double>& a, const std::vector<double>& b,
                             const std::vector<double>& c) {
  omp_set_num_threads(threads);
  const auto n = static_cast<std::int64_t>(a.size());
  const auto start = std::chrono::steady_clock::now();
  for (int r = 0; r < kTriadRepeats; ++r) {
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < n; ++i) a[i] = b[i] + 0.5 * c[i];
  }
  return seconds_since(start);
}

}  // namespace

MachineCeiling measure_machine_ceiling(int threads) {
  const common::ThreadScope caller_threads;
  MachineCeiling m;
  m.threads = threads;
  double sink = 0.0;
  compute_kernel_seconds(threads, sink);  // warm up the thread pool
  const double compute_one = compute_kernel_seconds(1, sink);
  const double compute_many = compute_kernel_seconds(threads, sink);
  m.compute_speedup = compute_one / compute_many;
  std::vector<double> a(kTriadLength, 0.0), b(kTriadLength, 1.0), c(kTriadLength, 2.0);
  const double memory_one = memory_kernel_seconds(1, a, b, c);
  const double memory_many = memory_kernel_seconds(threads, a, b, c);
  m.memory_speedup = memory_one / memory_many;
  if (sink == 0.0 || a[0] == 0.0) m.compute_speedup = 0.0;  // keeps the kernels from being optimised away
  return m;
}

}  // namespace ddafrac::app
