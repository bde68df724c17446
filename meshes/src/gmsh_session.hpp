#pragma once
// gmsh keeps one global model and option state. GmshSession owns it for the duration of one
// meshing or file operation: it initialises gmsh quietly and deterministically and finalises
// it again, so that nothing of ours outlives the call.

#include <string>
#include <utility>

#include "ddafrac/common/thread_scope.hpp"

namespace ddafrac::meshes::detail {

class GmshSession {
 public:
  GmshSession();
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

 private:
  // gmsh sets the process-wide OpenMP thread count from General.NumThreads; the caller's
  // count is restored on the way out (after gmsh is finalised, and when the constructor
  // throws), or a run after meshing would silently use one thread.
  common::ThreadScope caller_threads_;
};

/// The last error gmsh logged in this session (empty if none).
std::string gmsh_last_error();

/// Runs f (a sequence of gmsh API calls) and turns anything gmsh throws (std::string in gmsh
/// 4.8, or a std::exception) into a MeshError "<context>: <gmsh's message>".
[[noreturn]] void rethrow_gmsh_error(const std::string& context);

template <class F>
auto gmsh_call(const std::string& context, F&& f) {
  try {
    return std::forward<F>(f)();
  } catch (...) {
    rethrow_gmsh_error(context);
  }
}

}  // namespace ddafrac::meshes::detail
