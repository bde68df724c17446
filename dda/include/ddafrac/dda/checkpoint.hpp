#pragma once
// A run's checkpoint, RUN_DIR/checkpoint.bin: the engine's carried state and what the run loop
// has gathered for its files, so that `ddafrac run --resume RUN_DIR` continues bit for bit:
// the finished run's files are the ones an uninterrupted run writes. Written whole (temporary
// name, then rename), so a killed run always leaves the previous checkpoint or the new one.

#include <cstdint>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <string_view>

namespace ddafrac::dda {

inline constexpr std::string_view kCheckpointFile = "checkpoint.bin";

/// A checkpoint that cannot be read, or does not belong to the run it is asked to resume.
class CheckpointError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct Checkpoint {
  /// The caller's record of how the run was started (for `ddafrac run`: JSON with the scene
  /// file, its text after `base` and --set, and the options), so that a resume rebuilds it.
  std::string invocation;
  /// Fingerprint of the engine's carried state at t = 0: a resume checks that the scene and the
  /// mesh it rebuilt are the ones the run started from.
  std::uint64_t initial_state = 0;
  long step = 0;        // accepted steps when it was written
  double time = 0.0;    // s, simulated
  std::string engine;   // Engine::carried_state()
  std::string run_log;  // the run loop's own state (run.cpp)
};

/// 64-bit FNV-1a of the bytes: a fingerprint, not a cryptographic hash.
std::uint64_t fingerprint(std::string_view bytes);

void write_checkpoint(const std::filesystem::path& run_dir, const Checkpoint& checkpoint);

/// Reads RUN_DIR/checkpoint.bin. Throws CheckpointError naming the file and what is wrong
/// (missing, damaged, written by another format).
Checkpoint read_checkpoint(const std::filesystem::path& run_dir);

}  // namespace ddafrac::dda
