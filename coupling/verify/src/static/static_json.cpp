#include <nlohmann/json.hpp>

#include "comparison_json.hpp"
#include "static/static_report.hpp"

namespace ddafrac::coupling {

namespace {
nlohmann::json field(const FieldError& e) { return {{"all", e.all}, {"sxx", e.xx}, {"syy", e.yy}, {"txy", e.xy}}; }
nlohmann::json components(const reference::Stress2& s) { return {s.xx, s.yy, s.xy}; }
nlohmann::json pair(const CentreError& e) { return {e.xx, e.yy}; }
}  // namespace

std::string static_json(const StaticResults& r, double young) {
  const StaticComparison& c = r.comparison;
  nlohmann::json j = comparison_json(
      {"static", r.dda.blocks.size(), r.dda.steps, r.dda.wall, r.fem.wall, r.fem.dofs, r.dda.kn / young});
  j["load"] = r.setup.load;
  j["last_step_ratio"] = r.dda.last_step_ratio;
  j["anchor_force"] = r.dda.anchor_force;
  j["field_l2_fem"] = field(c.dda_fem);
  j["field_l2_fem_inner"] = c.dda_fem_inner.all;
  if (c.has_centre) {
    j["centre"] = {{"dda", components(c.centre_dda)}, {"fem", components(c.centre_fem)}};
    j["centre_error_fem"] = pair(c.centre_dda_fem);
  }
  if (r.setup.analytic) {
    j["field_l2_analytic"] = field(c.dda_ana);
    j["field_l2_fem_vs_analytic"] = c.fem_ana.all;
    if (c.has_centre) {
      j["centre"]["analytic"] = components(c.centre_ana);
      j["centre_error_analytic"] = pair(c.centre_dda_ana);
    }
  }
  j["worst_reasons"] = c.worst_where;
  return j.dump(2) + "\n";
}

}  // namespace ddafrac::coupling
