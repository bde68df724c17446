#include "ddafrac/fem/elasticity.hpp"

namespace ddafrac::fem {

StressSample make_sample(double x, double y, const Stress2& stress) {
  const auto p = reference::principal(stress);
  return {x, y, stress, p.s1, p.s3};
}

}  // namespace ddafrac::fem
