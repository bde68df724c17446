#pragma once
// Starting and waiting for child processes (sweep runs, the plotting script).

#include <sys/types.h>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace ddafrac::app {

/// Starts `argv` (argv[0] is the program path, unless `program` is given) with stdout and stderr
/// appended to `log` (or inherited if `log` is empty), with this process's environment or, if
/// given, with `environment` ("NAME=value" entries). Throws std::runtime_error if it cannot start.
pid_t spawn_process(const std::vector<std::string>& argv, const std::filesystem::path& log = {},
                    const std::optional<std::vector<std::string>>& environment = std::nullopt,
                    const std::filesystem::path& program = {});

/// The program path that starts this very executable even after its file was rebuilt or deleted
/// (Linux keeps the running file's inode): a sweep's or study's runs all use the engine that
/// began it, and a rebuild while it runs neither stops it nor mixes two engines in its results.
inline const std::filesystem::path kThisExecutable = "/proc/self/exe";

/// This process's environment without what an MPI launcher (mpirun, srun) gives its ranks
/// (OMPI_*, PMIX_*, PMI_*): a child started from a rank with those would take itself for that
/// rank, and were it to start MPI it would hang or fail.
std::vector<std::string> environment_outside_mpi();

struct Finished {
  pid_t pid = 0;
  int exit_code = 0;  // 128 + signal number if it was killed
};

/// Waits for any child to finish.
Finished wait_for_any_child();

/// A child that has finished, if any has, without waiting.
std::optional<Finished> finished_child();

/// Runs `argv` to completion; returns its exit code.
int run_process(const std::vector<std::string>& argv, const std::filesystem::path& log = {});

/// The path of the running executable, as a command line names it (scripts, messages).
std::filesystem::path own_executable();

}  // namespace ddafrac::app
