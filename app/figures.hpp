#pragma once
// Figures are drawn by plots/ddafrac_plots.py (matplotlib), so that researchers can restyle
// them by editing one small script; this runs it.

#include <filesystem>
#include <string>
#include <vector>

namespace ddafrac::app {

/// Runs `ddafrac_plots.py <arguments>`. Returns false (after saying why on stderr) if the
/// figures could not be drawn; the run's data files are complete either way.
bool draw_figures(const std::vector<std::string>& arguments);

/// Removes from `run_dir`/figures the figures `ddafrac_plots.py run` draws (energy, crack
/// counts, gauges, crack patterns, and their temporaries) and nothing else; returns how many.
std::size_t remove_previous_figures(const std::filesystem::path& run_dir);

}  // namespace ddafrac::app
