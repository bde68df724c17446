#pragma once
// Figures are drawn by plots/ddafrac_plots.py (matplotlib), so that researchers can restyle
// them by editing one small script; this runs it.

#include <string>
#include <vector>

namespace ddafrac::app {

/// Runs `ddafrac_plots.py <arguments>`. Returns false (after saying why on stderr) if the
/// figures could not be drawn; the run's data files are complete either way.
bool draw_figures(const std::vector<std::string>& arguments);

}  // namespace ddafrac::app
