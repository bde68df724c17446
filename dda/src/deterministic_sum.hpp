#pragma once
// A parallel sum whose result does not depend on the thread count: terms are added in fixed
// chunks, and the chunk sums in order. Internal to the DDA library; docs/design.md §10.2.

#include <algorithm>
#include <cstdint>
#include <vector>

namespace ddafrac::dda::detail {

/// Terms per chunk: the chunking, not the thread count, fixes the summation order.
constexpr std::int64_t kSumChunk = 256;

/// Σ term(i) for i in [0, n), bit-identical for any OMP_NUM_THREADS. T is any value-initialised
/// type with +=: a double, or a record of several sums taken in one pass. term(i) may change
/// item i (and nothing else), so that one pass can both sum and update a list.
template <class T = double, class F>
T chunked_sum(std::int64_t n, F&& term) {
  const std::int64_t chunks = (n + kSumChunk - 1) / kSumChunk;
  std::vector<T> part(static_cast<std::size_t>(chunks), T{});
#pragma omp parallel for schedule(static)
  for (std::int64_t c = 0; c < chunks; ++c) {
    T s{};
    const std::int64_t end = std::min(n, (c + 1) * kSumChunk);
    for (std::int64_t i = c * kSumChunk; i < end; ++i) s += term(i);
    part[c] = s;
  }
  T s{};
  for (const T& v : part) s += v;
  return s;
}

}  // namespace ddafrac::dda::detail
