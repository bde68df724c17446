#pragma once
// What parallel speed-up this machine can give at all, measured beside the benchmark: an
// embarrassingly parallel compute-bound kernel and a memory-bound one (stream triad), each timed
// with 1 and with N threads. On shared or SMT machines these ceilings are well below N, and the
// engine's own speed-up should be read against them, not against N.

namespace ddafrac::app {

struct MachineCeiling {
  int threads = 0;
  double compute_speedup = 0.0;  // time(1 thread) / time(N threads), dependent FP chains
  double memory_speedup = 0.0;   // the same for a triad over arrays far larger than the caches
};

/// Runs both kernels (about a second each on one thread); restores the OpenMP thread count.
MachineCeiling measure_machine_ceiling(int threads);

}  // namespace ddafrac::app
