#pragma once
// The process-wide OpenMP thread count, saved on entering a scope and restored on leaving it
// (also by an exception): for code that sets the count for a while (a comparison's DDA run, a
// speed measurement), or calls a library that sets it behind our back (gmsh).

namespace ddafrac::common {

class ThreadScope {
 public:
  /// Saves the present count and leaves it as it is.
  ThreadScope();
  /// Saves the present count and sets `threads` (at least 1).
  explicit ThreadScope(int threads);
  ~ThreadScope();
  ThreadScope(const ThreadScope&) = delete;
  ThreadScope& operator=(const ThreadScope&) = delete;

 private:
  int saved_;
};

}  // namespace ddafrac::common
