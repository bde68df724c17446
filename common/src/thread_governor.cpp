#include "ddafrac/common/thread_governor.hpp"

#include <omp.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

namespace ddafrac::common {

namespace {

/// Fields of the "cpu" line of /proc/stat: user nice system idle iowait irq softirq steal
/// (guest time is already inside user). Idle and iowait are the free time; steal (the
/// hypervisor running someone else on the core) is time the core was not ours.
constexpr int kStatFields = 8;
constexpr int kIdleField = 3, kIoWaitField = 4;
/// utime and stime are fields 14 and 15 of /proc/self/stat (1-based), after the ")" of the name.
constexpr int kOwnUserFieldAfterName = 12;

double wall_seconds() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

int machine_cpus() {
  const long n = ::sysconf(_SC_NPROCESSORS_ONLN);
  return n > 0 ? static_cast<int>(n) : 1;
}

}  // namespace

std::optional<CpuTimes> read_cpu_times() {
  CpuTimes t;
  {
    std::ifstream stat("/proc/stat");
    std::string label;
    if (!(stat >> label) || label != "cpu") return std::nullopt;
    for (int f = 0; f < kStatFields; ++f) {
      double ticks = 0.0;
      if (!(stat >> ticks)) return std::nullopt;
      t.machine_total += ticks;
      if (f != kIdleField && f != kIoWaitField) t.machine_busy += ticks;
    }
  }
  std::ifstream self("/proc/self/stat");
  std::string line;
  if (!std::getline(self, line)) return std::nullopt;
  const std::size_t name_end = line.rfind(')');
  if (name_end == std::string::npos) return std::nullopt;
  std::istringstream rest(line.substr(name_end + 1));
  std::string field;
  for (int f = 0; f < kOwnUserFieldAfterName - 1; ++f)
    if (!(rest >> field)) return std::nullopt;
  double utime = 0.0, stime = 0.0;
  if (!(rest >> utime >> stime)) return std::nullopt;
  t.own = utime + stime;
  return t;
}

double busy_cores_of_others(const CpuTimes& earlier, const CpuTimes& later, int cpus) {
  const double total = later.machine_total - earlier.machine_total;
  if (!(total > 0.0)) return 0.0;
  const double others = (later.machine_busy - earlier.machine_busy) - (later.own - earlier.own);
  return std::clamp(others / total * cpus, 0.0, static_cast<double>(cpus));
}

int threads_for(double others, int cores, int most, int current) {
  const double free = static_cast<double>(cores) - others;
  int threads = current;
  // Fewer when the free cores fall clearly below the count, more when they clearly exceed it.
  while (threads > 1 && free < threads - kGovernorHysteresis) --threads;
  while (threads < most && free > threads + 1 - kGovernorHysteresis) ++threads;
  return std::clamp(threads, 1, std::max(1, most));
}

ThreadGovernor::ThreadGovernor(int most)
    : most_(std::max(1, most)), cores_(std::max(1, omp_get_num_procs())), machine_cpus_(machine_cpus()) {
  threads_ = most_;
}

void ThreadGovernor::apply(int threads) {
  threads_ = threads;
  omp_set_num_threads(threads);
}

int ThreadGovernor::start(double sample_seconds) {
  last_ = read_cpu_times();
  if (last_) {
    std::this_thread::sleep_for(std::chrono::duration<double>(sample_seconds));
    const std::optional<CpuTimes> now = read_cpu_times();
    const double others = now ? busy_cores_of_others(*last_, *now, machine_cpus_) : 0.0;
    last_ = now;
    apply(threads_for(others, cores_, most_, most_));
  } else {
    apply(most_);
  }
  last_wall_ = wall_seconds();
  return threads_;
}

int ThreadGovernor::update(double interval_seconds) {
  const double wall = wall_seconds();
  if (!last_ || wall - last_wall_ < interval_seconds) return threads_;
  const std::optional<CpuTimes> now = read_cpu_times();
  if (!now) return threads_;
  apply(threads_for(busy_cores_of_others(*last_, *now, machine_cpus_), cores_, most_, threads_));
  last_ = now;
  last_wall_ = wall;
  return threads_;
}

}  // namespace ddafrac::common
