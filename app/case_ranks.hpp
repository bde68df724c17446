#pragma once
// The ranks of a sweep or a study started by an MPI launcher (`mpirun -np N ddafrac sweep ...`,
// `srun ddafrac sweep ...`): rank 0 hands the cases out one at a time, longest expected first,
// to whichever rank has a free slot (itself included), collects how each ended and writes the
// tables; every rank runs its cases as `ddafrac run` processes, as on one machine. Started
// plainly, the command is one rank and MPI is never started.

#include <string>
#include <vector>

namespace ddafrac::app {

struct CaseRun;
struct CaseRunSettings;

/// Joins MPI for the life of a command if an MPI launcher started this process; one rank if not.
class CaseRanks {
 public:
  CaseRanks();
  ~CaseRanks();  // leaves MPI (every rank must reach this: it waits for the others)
  CaseRanks(const CaseRanks&) = delete;
  CaseRanks& operator=(const CaseRanks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  bool is_root() const { return rank_ == 0; }  // the rank that hands out cases and writes tables

  /// The cores this rank's runs may use: those it may run on (all of the machine's when started
  /// plainly; those the launcher bound it to under MPI), shared with the other ranks of the node
  /// that may run on the same ones. Under MPI, a command's "runs at once" counts per rank.
  int cores_for_runs() const;

  /// " on rank R of N (host)" for the lines a rank prints; empty when started plainly.
  std::string where() const;

 private:
  bool joined_ = false;    // started by an MPI launcher: one of `size_` ranks
  bool finalize_ = false;  // MPI was started here, so it is ended here
  int rank_ = 0;
  int size_ = 1;
  int ranks_sharing_cores_ = 1;  // this one and the others of its node that may run on its cores
  std::string host_;
};

/// run_cases over the ranks (case_runs.hpp): the cases' entries on rank 0 end with every case's
/// exit code and wall time; the other ranks' hold only their own cases'.
void run_cases_over_ranks(std::vector<CaseRun>& cases, const CaseRunSettings& settings, const CaseRanks& ranks);

}  // namespace ddafrac::app
