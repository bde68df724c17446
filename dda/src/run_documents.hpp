#pragma once
// The documents of a run directory, one function each: history.csv rows, cracks.csv,
// crack_intervals.csv, run.pvd, summary.json and the VTU snapshot (run.hpp). Internal to the
// dda library: run.cpp owns when they are written, these own what they say.

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "ddafrac/dda/drive.hpp"  // kTimeSlack
#include "ddafrac/dda/run.hpp"

namespace ddafrac::dda {

std::string history_header();
/// One history.csv row of an accepted step.
std::string history_row(const StepReport& r);

std::string cracks_document(const std::vector<CrackEvent>& cracks);

/// New cracks per interval [k·w, (k+1)·w) from t = 0 up to the interval holding `time`.
std::string crack_intervals_document(const std::vector<CrackEvent>& cracks, double width, double time);

struct Snapshot {
  double time;
  std::string file;  // relative to the run directory
};

std::string pvd_document(const std::vector<Snapshot>& snaps);

/// fragments.csv: for each body with virtual joints, at t = 0, at every output interval and now:
/// crack counts and lengths, fragments and the largest fragment (crack_metrics.hpp).
std::string fragments_document(const Engine& e);

/// summary.json's "crack_metrics": the same measures now, with the first and the first
/// through-going crack's times and the definitions they rest on.
nlohmann::json crack_metrics_json(const Engine& e);

/// summary.json of the run so far; `loading` is its "loading" entry.
nlohmann::json summary_json(const Engine& e, const RunOptions& o, const RunResult& r, const nlohmann::json& loading);

}  // namespace ddafrac::dda
