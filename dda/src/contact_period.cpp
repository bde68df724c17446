#include "ddafrac/dda/contact_period.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "ddafrac/common/angles.hpp"

namespace ddafrac::dda {

ContactPeriod shortest_contact_period(const Engine& engine, double dt) {
  const BlockSystem& blocks = engine.blocks();
  const scene::Scene& scene = engine.scene();
  ContactPeriod out;
  out.stiffness = scene.analysis.penalty;
  for (const scene::JointSet& joints : scene.joint_sets)
    out.stiffness = std::max(out.stiffness, joints.normal_stiffness);
  if (out.stiffness <= 0.0) return out;
  constexpr double kReducedMassFraction = 0.5;  // two equal blocks on one spring
  auto period_of = [&](double mass) {
    return 2.0 * common::kPi * std::sqrt(kReducedMassFraction * mass / out.stiffness);
  };
  double lightest = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < blocks.block_count(); ++b) {
    const Index body = blocks.body[b];
    if (body >= 0 && scene.bodies[static_cast<std::size_t>(body)].motion != scene::Motion::Free) continue;
    ++out.moving_blocks;
    if (period_of(blocks.mass[b]) < kMinStepsPerContactPeriod * dt) ++out.unresolved_blocks;
    if (blocks.mass[b] < lightest) {
      lightest = blocks.mass[b];
      out.x = blocks.geometry[b].cx;
      out.y = blocks.geometry[b].cy;
    }
  }
  if (out.moving_blocks == 0) return out;
  out.mass = lightest;
  out.period = period_of(lightest);
  return out;
}

}  // namespace ddafrac::dda
