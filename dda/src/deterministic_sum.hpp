#pragma once
// A parallel sum whose result does not depend on the thread count: terms are added in fixed
// chunks, and the chunk sums in order. Internal to the DDA library.

#include <algorithm>
#include <cstdint>
#include <vector>

namespace ddafrac::dda::detail {

/// Terms per chunk: the chunking, not the thread count, fixes the summation order.
constexpr std::int64_t kSumChunk = 256;

/// Σ term(i) for i in [0, n), bit-identical for any OMP_NUM_THREADS.
template <class F>
double chunked_sum(std::int64_t n, F&& term) {
  const std::int64_t chunks = (n + kSumChunk - 1) / kSumChunk;
  std::vector<double> part(static_cast<std::size_t>(chunks), 0.0);
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < chunks; ++c) {
    double s = 0.0;
    const std::int64_t end = std::min(n, (c + 1) * kSumChunk);
    for (std::int64_t i = c * kSumChunk; i < end; ++i) s += term(i);
    part[c] = s;
  }
  double s = 0.0;
  for (double v : part) s += v;
  return s;
}

}  // namespace ddafrac::dda::detail
