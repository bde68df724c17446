#pragma once
// The OpenMP thread count of a comparison's DDA run, restored on leaving (also by an exception).

#include <omp.h>

#include <algorithm>

namespace ddafrac::coupling {

class ThreadScope {
 public:
  explicit ThreadScope(int threads) : saved_(omp_get_max_threads()) { omp_set_num_threads(std::max(1, threads)); }
  ~ThreadScope() { omp_set_num_threads(saved_); }
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int saved_;
};

}  // namespace ddafrac::coupling
