#include "study_source_report.hpp"

#include <fmt/core.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <map>

namespace ddafrac::app {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr double kMicrosecondsPerSecond = 1e6;
constexpr double kMillimetresPerMetre = 1e3;
constexpr double kKilonewtonsPerNewton = 1e-3;
constexpr double kPercent = 100.0;

/// The number at a path of keys, or nothing.
std::optional<double> number_at(const json& j, std::initializer_list<const char*> keys) {
  const json* node = &j;
  for (const char* key : keys) {
    if (!node->is_object() || !node->contains(key)) return std::nullopt;
    node = &(*node)[key];
  }
  return node->is_number() ? std::optional<double>(node->get<double>()) : std::nullopt;
}

std::string cell(const std::optional<double>& v, const char* format, double scale = 1.0) {
  return v ? fmt::format(fmt::runtime(format), *v * scale) : std::string("–");
}

/// The largest |force_y| of the prescribed bodies (N/m), if the run had any.
std::optional<double> peak_force(const json& summary) {
  std::optional<double> peak;
  if (!summary.contains("loading") || !summary["loading"].contains("peak")) return peak;
  for (const auto& [body, p] : summary["loading"]["peak"].items())
    if (const auto f = number_at(p, {"peak_abs_force_y"})) peak = std::max(peak.value_or(0.0), *f);
  return peak;
}

/// A row of the case table, and whether its times are a static run's load parameter.
struct TableRow {
  std::string text;
  bool pseudo_time = false;
};

/// Marks a static run's times: there, t is a load parameter (the platen's travel over its
/// speed), not a time, so it is printed in s and never as µs of a dynamic run.
constexpr const char* kPseudoTimeMark = "†";

/// The case's name, and the case whose run it shows if it repeats that case's scene.
std::string case_cell(const StudyCase& c) {
  return c.repeat_of.empty() ? c.run.scene.name : fmt::format("{} ({}'s run)", c.run.scene.name, c.repeat_of);
}

TableRow table_row(const StudyCase& c) {
  const json s = read_summary(c.run.run_dir);
  if (s.is_discarded()) {
    const std::string state = c.run.exit_code > 0 ? fmt::format(
                                                        "failed before its first output (exit status {}; "
                                                        "see its run.log)",
                                                        c.run.exit_code)
                                                  : std::string("not run");
    return {fmt::format("| {} | {} | {} |{}\n", case_cell(c), c.series, state, std::string(15, '|'))};
  }
  const bool pseudo_time = s.contains("scene") && s["scene"].value("mode", "") == "static";
  // A time in µs (`format`), or a static run's load parameter in s.
  const auto time_cell = [pseudo_time](const std::optional<double>& t, const char* format) {
    return pseudo_time ? cell(t, "{:.4g} s") + (t ? kPseudoTimeMark : "") : cell(t, format, kMicrosecondsPerSecond);
  };
  const json metrics = s.value("crack_metrics", json::object());
  std::optional<double> length;
  if (const auto t = number_at(metrics, {"crack_length_tensile"}))
    length = *t + number_at(metrics, {"crack_length_shear"}).value_or(0.0);
  std::optional<double> largest;
  if (metrics.contains("bodies") && metrics["bodies"].size() == 1)
    largest = number_at(metrics["bodies"][0], {"largest_fragment_fraction"});
  std::optional<double> cuts;
  for (const char* kind : {"cuts_displacement", "cuts_open_close", "cuts_solver"})
    if (const auto n = number_at(s, {"dt", kind})) cuts = cuts.value_or(0.0) + *n;
  const std::string reason = s.contains("exit") ? s["exit"].value("reason", "?") : "?";
  const std::string text = fmt::format(
      "| {} | {} | {} | {} | {} | {} | {} | {} / {} | {} | {} | {} | {} | {} | {} | {} | {} | {} / {} | {} |\n",
      case_cell(c), c.series, cell(number_at(s, {"scene", "blocks"}), "{:.0f}"),
      cell(number_at(s, {"steps"}), "{:.0f}"), cell(cuts, "{:.0f}"),
      cell(number_at(s, {"wall_time", "total"}), "{:.1f}"), time_cell(number_at(s, {"simulated_time"}), "{:.0f}"),
      cell(number_at(s, {"cracks", "tensile"}), "{:.0f}"), cell(number_at(s, {"cracks", "shear"}), "{:.0f}"),
      cell(length, "{:.1f}", kMillimetresPerMetre), cell(number_at(metrics, {"fragments"}), "{:.0f}"),
      cell(largest, "{:.1f}", kPercent), time_cell(number_at(metrics, {"first_crack_time"}), "{:.1f}"),
      time_cell(number_at(metrics, {"first_through_crack_time"}), "{:.1f}"),
      cell(peak_force(s), "{:.2f}", kKilonewtonsPerNewton),
      cell(number_at(s, {"energy", "largest_balance_error"}), "{:.2g}", kPercent),
      cell(number_at(s, {"missed_contacts", "count"}), "{:.0f}"),
      cell(number_at(s, {"joint_load_share", "normal"}), "{:.2f}"),
      cell(number_at(s, {"joint_load_share", "shear"}), "{:.2f}"), reason);
  return {text, pseudo_time};
}

/// The crack-metric definitions as the runs wrote them (so the report cannot drift from the code).
std::string definitions(const std::vector<StudyCase>& cases) {
  for (const StudyCase& c : cases) {
    const json s = read_summary(c.run.run_dir);
    if (s.is_discarded() || !s.contains("crack_metrics")) continue;
    const json& d = s["crack_metrics"]["definitions"];
    std::string md =
        fmt::format("- fragment: {}\n- through-going crack: {} (through_fragment_fraction = {})\n",
                    d.value("fragment", ""), d.value("through_crack", ""), d.value("through_fragment_fraction", 0.0));
    if (s.contains("joint_load_share"))
      md += fmt::format("- joints' load share: {}\n", s["joint_load_share"].value("definition", ""));
    return md;
  }
  return "- (no run has written its crack metrics yet)\n";
}

/// Which engine (the source commit of the ddafrac build) ran each case, as the runs recorded it:
/// cases of one study run by different engines can differ by more than the physics does.
std::string engines(const std::vector<StudyCase>& cases) {
  const std::string not_recorded = "not recorded (a build before runs recorded it)";
  std::map<std::string, std::vector<std::string>> cases_by_commit;
  for (const StudyCase& c : cases) {
    const json s = read_summary(c.run.run_dir);
    if (s.is_discarded()) continue;
    cases_by_commit[s.value("ddafrac_commit", not_recorded)].push_back(c.run.scene.name);
  }
  if (cases_by_commit.empty()) return "";
  if (cases_by_commit.size() == 1) {
    const std::string& commit = cases_by_commit.begin()->first;
    return commit == not_recorded
               ? "\nEngine: " + not_recorded + ".\n"
               : fmt::format("\nEngine: the cases run so far were all run by the build of commit `{}`.\n", commit);
  }
  std::string md =
      "\nEngines (the source commit of the build that ran each case; \"-dirty\": with uncommitted changes):\n";
  for (const auto& [commit, names] : cases_by_commit) md += fmt::format("- `{}`: {}\n", commit, fmt::join(names, ", "));
  return md;
}

}  // namespace

std::string case_table(const std::vector<StudyCase>& cases) {
  std::string md = "Crack metrics:\n" + definitions(cases) + "\n";
  md +=
      "| case | series | blocks | steps | dt cuts | wall (s) | t end (µs) | cracks tensile / shear | crack length (mm) "
      "| fragments | largest fragment (%) | first crack (µs) | through crack (µs) | peak force (kN/m) "
      "| largest energy-balance error (%) | missed contacts | joints' load share, normal / shear | exit |\n";
  md += "|---|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|---|\n";
  bool pseudo_time = false;
  for (const StudyCase& c : cases) {
    const TableRow row = table_row(c);
    md += row.text;
    pseudo_time = pseudo_time || row.pseudo_time;
  }
  if (pseudo_time)
    md += fmt::format(
        "\n{} static mode: t is a load parameter, the platen's travel over its speed (s), not a time; "
        "compare platen travel, not t, with the dynamic runs.\n",
        kPseudoTimeMark);
  return md + engines(cases);
}

std::string study_markdown(const std::vector<StudyCase>& cases, const std::vector<std::string>& overrides,
                           const std::vector<std::string>& figures) {
  std::string md = "# The source study\n\n";
  md += fmt::format(
      "Written by `ddafrac study source`{}. Every number below is read from the case's "
      "`summary.json`; a case not run yet says so, and a dash marks a measure a run did not reach. "
      "The Brazilian discs' peak forces, indirect tensile strengths and the flattened disc's mesh "
      "convergence are in [analysis.md](analysis.md), written with the figures.\n\n",
      overrides.empty() ? std::string(" at full size")
                        : fmt::format(" with `--set {}`", fmt::join(overrides, " --set ")));
  md += case_table(cases);
  if (!figures.empty()) {
    md += "\n## Figures\n\n";
    for (const std::string& f : figures) md += fmt::format("![{}]({})\n\n", f, f);
  }
  return md;
}

}  // namespace ddafrac::app
