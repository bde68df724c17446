#include "case_ranks.hpp"

#include <fmt/core.h>
#include <sched.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <deque>
#include <exception>
#include <map>
#include <thread>

#include "case_runs.hpp"
#include "commands.hpp"
#include "subprocess.hpp"

#ifdef DDAFRAC_WITH_MPI
#include <mpi.h>
#endif

namespace ddafrac::app {

namespace {

using Clock = std::chrono::steady_clock;

/// The variables by which a process knows an MPI launcher started it: Open MPI's mpirun, a
/// PMIx launcher (srun --mpi=pmix, prterun), a PMI-1/2 launcher (MPICH's mpiexec, srun
/// --mpi=pmi2). A plain start has none of them and never starts MPI: there is nothing to share,
/// and a one-rank MPI start costs about a second and needs a working MPI runtime.
bool started_by_mpi_launcher() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

/// The cores this process may run on (its affinity mask: what a launcher's binding leaves it).
cpu_set_t cores_allowed() {
  cpu_set_t set;
  CPU_ZERO(&set);
  if (sched_getaffinity(0, sizeof(set), &set) != 0)
    for (unsigned core = 0; core < std::max(1u, std::thread::hardware_concurrency()); ++core) CPU_SET(core, &set);
  return set;
}

}  // namespace

int CaseRanks::cores_for_runs() const {
  const cpu_set_t allowed = cores_allowed();
  return std::max(1, CPU_COUNT(&allowed) / ranks_sharing_cores_);
}

std::string CaseRanks::where() const {
  return joined_ ? fmt::format(" on rank {} of {} ({})", rank_, size_, host_) : std::string();
}

#ifndef DDAFRAC_WITH_MPI

CaseRanks::CaseRanks() {
  if (started_by_mpi_launcher())
    throw CommandFailed(
        "started by an MPI launcher, but this ddafrac was built without MPI (every rank would run every case): "
        "run it without mpirun/srun, or use --emit-slurm");
}
CaseRanks::~CaseRanks() = default;

void run_cases_over_ranks(std::vector<CaseRun>&, const CaseRunSettings&, const CaseRanks&) {}

#else

namespace {

std::string host_name() {
  std::array<char, 256> name{};
  return gethostname(name.data(), name.size() - 1) == 0 ? std::string(name.data()) : std::string("?");
}

/// The messages between rank 0 and the others. A rank with a free slot asks for a case; rank 0
/// answers with a case (index into the cases, how it starts) or with "no more"; a rank whose
/// case ended tells rank 0 (index, exit code, wall seconds).
constexpr int kAskTag = 1;
constexpr int kCaseTag = 2;
constexpr int kEndedTag = 3;
constexpr int kNoMoreCases = -1;
constexpr int kRoot = 0;

/// How often rank 0, which runs cases of its own too, looks for ended runs and for messages
/// when neither came: far below a case's length, far above the cost of a look.
constexpr auto kRootPollInterval = std::chrono::milliseconds(20);

using CaseMessage = std::array<int, 2>;      // case index (or kNoMoreCases), Start
using EndedMessage = std::array<double, 3>;  // case index, exit code, wall seconds

struct Running {
  std::size_t index;
  Clock::time_point started;
};

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

/// Rank 0's side: the queue of cases, longest expected first, handed to itself and to the
/// ranks that ask; each ended case is recorded in `cases` and printed, and after_each is called.
class Dispatcher {
 public:
  Dispatcher(std::vector<CaseRun>& cases, const CaseRunSettings& settings, const CaseRanks& ranks)
      : cases_(cases), settings_(settings), ranks_(ranks) {
    const std::vector<std::size_t> order = dispatch_order(cases);
    queue_.assign(order.begin(), order.end());
    done_ = cases.size() - order.size();
  }

  void run(int slots) {
    while (done_ < cases_.size() || released_ < ranks_.size() - 1) {
      while (static_cast<int>(own_.size()) < slots && !queue_.empty()) start_own(take());
      const bool busy = collect_own() | answer_message();
      if (!busy) std::this_thread::sleep_for(kRootPollInterval);
    }
  }

 private:
  std::size_t take() {
    const std::size_t index = queue_.front();
    queue_.pop_front();
    return index;
  }

  void start_own(std::size_t index) {
    own_[start_case(cases_[index], settings_, ranks_.where())] = {index, Clock::now()};
  }

  bool collect_own() {
    const std::optional<Finished> finished = finished_child();
    if (!finished) return false;
    const auto it = own_.find(finished->pid);
    if (it == own_.end()) return true;
    ended(it->second.index, finished->exit_code, seconds_since(it->second.started), fmt::format(" on rank {}", kRoot));
    own_.erase(it);
    return true;
  }

  bool answer_message() {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &arrived, &status);
    if (!arrived) return false;
    if (status.MPI_TAG == kAskTag) {
      int ask = 0;
      MPI_Recv(&ask, 1, MPI_INT, status.MPI_SOURCE, kAskTag, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      CaseMessage answer{kNoMoreCases, 0};
      if (queue_.empty()) {
        ++released_;
      } else {
        const std::size_t index = take();
        answer = {static_cast<int>(index), static_cast<int>(cases_[index].start)};
      }
      MPI_Send(answer.data(), static_cast<int>(answer.size()), MPI_INT, status.MPI_SOURCE, kCaseTag, MPI_COMM_WORLD);
    } else {
      EndedMessage message{};
      MPI_Recv(message.data(), static_cast<int>(message.size()), MPI_DOUBLE, status.MPI_SOURCE, kEndedTag,
               MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      ended(static_cast<std::size_t>(message[0]), static_cast<int>(message[1]), message[2],
            fmt::format(" on rank {}", status.MPI_SOURCE));
    }
    return true;
  }

  void ended(std::size_t index, int exit_code, double seconds, const std::string& where) {
    CaseRun& c = cases_[index];
    c.exit_code = exit_code;
    c.wall_seconds = seconds;  // the running rank's, a resumed run's parts included
    print_end(c, ++done_, cases_.size(), where);
    if (settings_.after_each) settings_.after_each();
  }

  std::vector<CaseRun>& cases_;
  const CaseRunSettings& settings_;
  const CaseRanks& ranks_;
  std::deque<std::size_t> queue_;
  std::map<pid_t, Running> own_;
  std::size_t done_ = 0;
  int released_ = 0;  // ranks told there are no more cases
};

/// The other ranks' side: ask for a case while a slot is free, run it, say how it ended.
void work_for_root(std::vector<CaseRun>& cases, const CaseRunSettings& settings, const CaseRanks& ranks, int slots) {
  std::map<pid_t, Running> running;
  bool more = true;
  while (more || !running.empty()) {
    while (more && static_cast<int>(running.size()) < slots) {
      int ask = 0;
      MPI_Send(&ask, 1, MPI_INT, kRoot, kAskTag, MPI_COMM_WORLD);
      CaseMessage answer{};
      MPI_Recv(answer.data(), static_cast<int>(answer.size()), MPI_INT, kRoot, kCaseTag, MPI_COMM_WORLD,
               MPI_STATUS_IGNORE);
      more = answer[0] != kNoMoreCases;
      if (!more) break;
      CaseRun& c = cases[static_cast<std::size_t>(answer[0])];
      c.start = static_cast<Start>(answer[1]);
      running[start_case(c, settings, ranks.where())] = {static_cast<std::size_t>(answer[0]), Clock::now()};
    }
    if (running.empty()) break;
    const Finished finished = wait_for_any_child();
    const auto it = running.find(finished.pid);
    if (it == running.end()) continue;
    CaseRun& c = cases[it->second.index];
    record_end(c, finished.exit_code, seconds_since(it->second.started));
    const EndedMessage message{static_cast<double>(it->second.index), static_cast<double>(c.exit_code), c.wall_seconds};
    MPI_Send(message.data(), static_cast<int>(message.size()), MPI_DOUBLE, kRoot, kEndedTag, MPI_COMM_WORLD);
    running.erase(it);
  }
}

/// How many ranks of this node (this one included) may run on exactly this rank's cores: all of
/// the node's when the launcher bound none (mpirun --bind-to none, srun without binding), one
/// when it bound each to cores of its own, those of a socket when it bound to sockets.
int ranks_with_my_cores() {
  MPI_Comm node;
  MPI_Comm_split_type(MPI_COMM_WORLD, MPI_COMM_TYPE_SHARED, 0, MPI_INFO_NULL, &node);
  int ranks = 1;
  MPI_Comm_size(node, &ranks);
  const cpu_set_t mine = cores_allowed();
  std::vector<cpu_set_t> all(static_cast<std::size_t>(ranks));
  MPI_Allgather(&mine, sizeof(cpu_set_t), MPI_BYTE, all.data(), sizeof(cpu_set_t), MPI_BYTE, node);
  MPI_Comm_free(&node);
  return static_cast<int>(
      std::count_if(all.begin(), all.end(), [&](const cpu_set_t& other) { return CPU_EQUAL(&other, &mine); }));
}

}  // namespace

CaseRanks::CaseRanks() {
  if (!started_by_mpi_launcher()) return;
  int already = 0;
  MPI_Initialized(&already);
  if (!already) MPI_Init(nullptr, nullptr);
  joined_ = true;
  finalize_ = !already;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  ranks_sharing_cores_ = ranks_with_my_cores();
  host_ = host_name();
}

CaseRanks::~CaseRanks() {
  if (finalize_) MPI_Finalize();
}

void run_cases_over_ranks(std::vector<CaseRun>& cases, const CaseRunSettings& settings, const CaseRanks& ranks) {
  // A rank that stops with an error while others wait for its messages would hang the job:
  // say what went wrong and end the job instead.
  try {
    if (ranks.is_root())
      Dispatcher(cases, settings, ranks).run(settings.parallel);
    else
      work_for_root(cases, settings, ranks, settings.parallel);
  } catch (const std::exception& e) {
    fmt::print(stderr, "ddafrac:{}: {}; ending the job\n", ranks.where(), e.what());
    std::fflush(stderr);
    MPI_Abort(MPI_COMM_WORLD, 1);
  }
}

#endif

}  // namespace ddafrac::app
