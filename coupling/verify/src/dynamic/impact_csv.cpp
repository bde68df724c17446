#include <fmt/core.h>

#include <sstream>
#include <utility>

#include "ddafrac/common/whole_file.hpp"
#include "dynamic/impact_report.hpp"

namespace ddafrac::coupling {

namespace {

/// Gauge histories of several models side by side: t,model,gauge,syy,s1.
std::string gauge_histories_csv(const std::vector<std::pair<std::string, const GaugeHistories*>>& models) {
  std::ostringstream text;
  text << "t,model,gauge,syy,s1\n";
  for (const auto& [label, h] : models)
    for (std::size_t g = 0; g < h->names.size(); ++g)
      for (std::size_t i = 0; i < h->syy[g].t.size(); ++i)
        text << fmt::format("{:.9g},{},{},{:.9g},{:.9g}\n", h->syy[g].t[i], label, h->names[g], h->syy[g].v[i],
                            h->s1[g].v[i]);
  return text.str();
}

std::string gauge_errors_csv(const scene::Scene& scene, const ImpactResults& r) {
  std::ostringstream csv;
  csv << "gauge,x,y,fem_peak_syy,fem_peak_time,dda_peak_syy,dda_peak_time,peak_error,fem_arrival,dda_arrival,"
         "arrival_error,arrival_checked,rms_over_peak_syy,rms_over_peak_s1,fem_half_one_rms_over_peak_syy\n";
  for (std::size_t g = 0; g < r.errors.size(); ++g) {
    const auto& e = r.errors[g];
    csv << fmt::format(
        "{},{:.6g},{:.6g},{:.9g},{:.9g},{:.9g},{:.9g},{:.6g},{:.9g},{:.9g},{:.6g},{},{:.6g},{:.6g},{:.6g}\n", e.gauge,
        scene.gauges[g].position[0], scene.gauges[g].position[1], e.syy.reference_peak.value, e.syy.reference_peak.time,
        e.syy.approximation_peak.value, e.syy.approximation_peak.time, e.peak_error, e.syy.reference_arrival,
        e.syy.approximation_arrival, e.arrival_error, e.arrival_checked ? 1 : 0, e.syy.rms_over_peak,
        e.s1_rms_over_peak, r.time_errors[g].syy.rms_over_peak);
  }
  return csv.str();
}

}  // namespace

void write_impact_csv(const std::filesystem::path& dir, const scene::Scene& scene, const ImpactResults& r) {
  std::filesystem::create_directories(dir);
  // "FEM-half-one": the FEM with the DDA's Newmark (½, 1); the plots know the runs by these labels.
  common::write_whole_text(
      dir / "impact_gauges.csv",
      gauge_histories_csv({{"FEM", &r.fem}, {"DDA", &r.dda}, {"FEM-half-one", &r.fem_dda_scheme}}));
  common::write_whole_text(dir / "impact_gauge_errors.csv", gauge_errors_csv(scene, r));
}

}  // namespace ddafrac::coupling
