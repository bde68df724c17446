#include "ddafrac/dda/contact_period.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ddafrac/common/angles.hpp"

namespace ddafrac::dda {

ContactPeriod shortest_contact_period(const Engine& engine) {
  const BlockSystem& blocks = engine.blocks();
  const scene::Scene& scene = engine.scene();
  double lightest = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < blocks.block_count(); ++b) {
    const Index body = blocks.body[b];
    const bool moves = body < 0 || scene.bodies[static_cast<std::size_t>(body)].motion == scene::Motion::Free;
    if (moves) lightest = std::min(lightest, blocks.mass[b]);
  }
  double stiffest = scene.analysis.penalty;
  for (const Contact& c : engine.contacts().contacts) stiffest = std::max(stiffest, c.kn);
  if (!std::isfinite(lightest) || stiffest <= 0.0) return {};
  constexpr double kReducedMassFraction = 0.5;  // two equal blocks on one spring
  return {2.0 * common::kPi * std::sqrt(kReducedMassFraction * lightest / stiffest), lightest, stiffest};
}

}  // namespace ddafrac::dda
