#include "subprocess.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <iterator>
#include <stdexcept>
#include <string_view>

extern char** environ;

namespace ddafrac::app {

namespace {
/// Exit code reported for a child killed by a signal, plus the signal number (shell convention).
constexpr int kSignalExitBase = 128;

int exit_code_of(int status) {
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  if (WIFSIGNALED(status)) return kSignalExitBase + WTERMSIG(status);
  return kSignalExitBase;
}

/// The pointer array exec wants: one per string, then a null.
std::vector<char*> c_strings(const std::vector<std::string>& strings) {
  std::vector<char*> pointers;
  for (const std::string& s : strings) pointers.push_back(const_cast<char*>(s.c_str()));
  pointers.push_back(nullptr);
  return pointers;
}

/// The prefixes of the variables Open MPI's mpirun (OMPI_), PMIx launchers such as srun
/// --mpi=pmix (PMIX_) and PMI-1/2 launchers such as MPICH's and srun --mpi=pmi2 (PMI_) give a rank.
constexpr std::string_view kMpiLauncherPrefixes[] = {"OMPI_", "PMIX_", "PMI_"};
}  // namespace

pid_t spawn_process(const std::vector<std::string>& argv, const std::filesystem::path& log,
                    const std::optional<std::vector<std::string>>& environment, const std::filesystem::path& program) {
  std::vector<char*> arguments = c_strings(argv);
  std::vector<char*> variables = environment ? c_strings(*environment) : std::vector<char*>();

  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  if (!log.empty()) {
    posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, STDOUT_FILENO, STDERR_FILENO);
  }
  pid_t pid = 0;
  const int error = posix_spawn(&pid, program.empty() ? arguments[0] : program.c_str(), &actions, nullptr,
                                arguments.data(), environment ? variables.data() : environ);
  posix_spawn_file_actions_destroy(&actions);
  if (error != 0) throw std::runtime_error("cannot start " + argv[0] + ": " + std::strerror(error));
  return pid;
}

Finished wait_for_any_child() {
  int status = 0;
  pid_t pid = 0;
  do {
    pid = waitpid(-1, &status, 0);
  } while (pid < 0 && errno == EINTR);
  if (pid < 0) throw std::runtime_error(std::string("waiting for a child process: ") + std::strerror(errno));
  return {pid, exit_code_of(status)};
}

std::vector<std::string> environment_outside_mpi() {
  std::vector<std::string> kept;
  for (char** entry = environ; *entry != nullptr; ++entry) {
    const std::string_view variable(*entry);
    const auto from_launcher = [&](std::string_view prefix) { return variable.substr(0, prefix.size()) == prefix; };
    if (std::none_of(std::begin(kMpiLauncherPrefixes), std::end(kMpiLauncherPrefixes), from_launcher))
      kept.emplace_back(variable);
  }
  return kept;
}

std::optional<Finished> finished_child() {
  int status = 0;
  pid_t pid = 0;
  do {
    pid = waitpid(-1, &status, WNOHANG);
  } while (pid < 0 && errno == EINTR);
  if (pid == 0 || (pid < 0 && errno == ECHILD)) return std::nullopt;
  if (pid < 0) throw std::runtime_error(std::string("waiting for a child process: ") + std::strerror(errno));
  return Finished{pid, exit_code_of(status)};
}

int run_process(const std::vector<std::string>& argv, const std::filesystem::path& log) {
  const pid_t pid = spawn_process(argv, log);
  int status = 0;
  while (waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error(std::string("waiting for ") + argv[0] + ": " + std::strerror(errno));
  }
  return exit_code_of(status);
}

std::filesystem::path own_executable() { return std::filesystem::read_symlink("/proc/self/exe"); }

}  // namespace ddafrac::app
