#pragma once
// OpenMP thread count from the cores other processes leave free. A step of the engine runs many
// short parallel regions, each ending in a barrier; when another process holds a core, the
// barrier waits for a descheduled thread for a whole scheduler time slice, and two threads run
// slower than one. The governor measures the CPU time the rest of the machine uses (/proc/stat
// minus this process's own, /proc/self/stat) and keeps threads + busy cores of others within
// the cores this process may use. Results do not depend on the thread count, so it may change
// between steps.

#include <optional>

namespace ddafrac::common {

/// Cumulative CPU time in clock ticks: of the whole machine (busy and total, all CPUs) and of
/// this process (user + system, all its threads).
struct CpuTimes {
  double machine_busy = 0.0, machine_total = 0.0, own = 0.0;
};

/// Reads the counters; nothing where /proc is not readable.
std::optional<CpuTimes> read_cpu_times();

/// Cores of the machine's CPUs that other processes kept busy between two readings
/// (0 <= result <= machine_cpus).
double busy_cores_of_others(const CpuTimes& earlier, const CpuTimes& later, int machine_cpus);

/// The thread count for `others` busy cores: the cores left free, at least 1, at most `most`.
/// Hysteresis of kGovernorHysteresis cores around each step keeps a count from flipping on
/// noise: the count changes only when the free cores differ from `current` by more than it.
int threads_for(double others, int cores, int most, int current);

/// Fraction of a core by which a measurement must cross the boundary before the count changes.
inline constexpr double kGovernorHysteresis = 0.3;

class ThreadGovernor {
 public:
  /// `most`: the largest count to use (the user's --threads, or the cores this process may use).
  explicit ThreadGovernor(int most);

  /// Measures the machine over `sample_seconds` while this process is idle and sets the OpenMP
  /// thread count; returns it.
  int start(double sample_seconds);

  /// Re-measures since the previous call (at most once per `interval_seconds` of wall time; call
  /// it between steps from the thread that opens the parallel regions) and sets the count;
  /// returns the count in use.
  int update(double interval_seconds);

  int threads() const { return threads_; }

 private:
  void apply(int threads);

  int most_ = 1, cores_ = 1, machine_cpus_ = 1;
  int threads_ = 1;
  std::optional<CpuTimes> last_;
  double last_wall_ = 0.0;
};

}  // namespace ddafrac::common
