#include "ddafrac/common/thread_scope.hpp"

#include <omp.h>

#include <algorithm>

namespace ddafrac::common {

ThreadScope::ThreadScope() : saved_(omp_get_max_threads()) {}

ThreadScope::ThreadScope(int threads) : ThreadScope() { omp_set_num_threads(std::max(1, threads)); }

ThreadScope::~ThreadScope() { omp_set_num_threads(saved_); }

}  // namespace ddafrac::common
