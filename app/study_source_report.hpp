#pragma once
// The study.md of `ddafrac study source` (one table row per case, read from each run's
// summary.json) and the case table `study sensitivity` shares.

#include <filesystem>
#include <string>
#include <vector>

#include "study_runs.hpp"

namespace ddafrac::app {

/// The crack-metric definitions the runs used and a table of every case (blocks, steps, dt
/// cuts, wall time, cracks, crack length, fragments, first and through-going crack, peak force,
/// energy-balance error, missed contacts, the joints' load share, how it ended), read from each run's
/// summary.json.
std::string case_table(const std::vector<StudyCase>& cases);

/// study.md: the settings, the crack-metric definitions the runs used, and a table of every
/// case (blocks, steps, dt cuts, wall time, cracks, crack length, fragments, first and
/// through-going crack, peak force, energy-balance error, missed contacts, the joints' load share,
/// how it ended).
std::string study_markdown(const std::vector<StudyCase>& cases, const std::vector<std::string>& overrides,
                           const std::vector<std::string>& figures);

}  // namespace ddafrac::app
