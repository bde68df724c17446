#pragma once
// What every comparison.json holds, static or impact: `ddafrac study convergence` reads blocks,
// steps and fem_dofs from either kind.

#include <nlohmann/json.hpp>

#include <cstddef>

namespace ddafrac::coupling {

struct ComparisonHead {
  const char* kind = "";  // "static" or "impact"
  std::size_t blocks = 0;
  long steps = 0;                         // DDA steps
  double dda_wall = 0.0, fem_wall = 0.0;  // s
  std::size_t fem_dofs = 0;
  double kn_over_e = 0.0;  // the DDA twin's joint stiffness / Young's modulus
};

inline nlohmann::json comparison_json(const ComparisonHead& h) {
  return {{"kind", h.kind},         {"blocks", h.blocks},     {"steps", h.steps},        {"dda_wall", h.dda_wall},
          {"fem_wall", h.fem_wall}, {"fem_dofs", h.fem_dofs}, {"kn_over_E", h.kn_over_e}};
}

}  // namespace ddafrac::coupling
