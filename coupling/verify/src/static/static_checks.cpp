#include "static/static_checks.hpp"

namespace ddafrac::coupling {

std::vector<Check> static_checks(const StaticSetup& st, const StaticComparison& c, const scene::Verification& tol) {
  std::vector<Check> checks;
  if (tol.centre_stress && c.has_centre) {
    checks.push_back({"centre sxx, DDA vs FEM", "centre_stress", c.centre_dda_fem.xx, *tol.centre_stress});
    checks.push_back({"centre syy, DDA vs FEM", "centre_stress", c.centre_dda_fem.yy, *tol.centre_stress});
    if (st.analytic) {
      checks.push_back({"centre sxx, DDA vs Hondros", "centre_stress", c.centre_dda_ana.xx, *tol.centre_stress});
      checks.push_back({"centre syy, DDA vs Hondros", "centre_stress", c.centre_dda_ana.yy, *tol.centre_stress});
    }
  }
  if (tol.field_l2) {
    checks.push_back({"field L2 (sxx, syy, txy), DDA vs FEM", "field_l2", c.dda_fem.all, *tol.field_l2});
    if (st.analytic)
      checks.push_back({"field L2 (sxx, syy, txy), DDA vs Hondros", "field_l2", c.dda_ana.all, *tol.field_l2});
  }
  return checks;
}

}  // namespace ddafrac::coupling
