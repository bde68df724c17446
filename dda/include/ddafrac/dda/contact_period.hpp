#pragma once
// The shortest period a contact spring can have in a model: two of its lightest blocks on the
// stiffest spring, T = 2π·√(m_r / kn) with the reduced mass m_r = m/2. A time step that is not
// a small fraction of it cannot follow the contact: blocks rock and bounce instead of resting
// (docs/design.md §7).

#include "ddafrac/dda/engine.hpp"

namespace ddafrac::dda {

/// Steps per contact period below which a run is warned. The time scheme (Newmark, average
/// acceleration) lengthens an oscillator's period by about (ω·dt)²/12: 5% at 8 steps per
/// period, and the error grows with the square of the step.
inline constexpr double kMinStepsPerContactPeriod = 8.0;

struct ContactPeriod {
  double period = 0.0;      // s
  double mass = 0.0;        // kg per unit thickness, of the lightest block
  double stiffness = 0.0;   // N/m per unit thickness, the stiffest contact spring
  double x = 0.0, y = 0.0;  // m, centroid of the lightest block
  /// Moving blocks whose own period on the stiffest spring is shorter than `dt` times
  /// kMinStepsPerContactPeriod (the `dt` passed in).
  std::size_t unresolved_blocks = 0;
  std::size_t moving_blocks = 0;
};

/// Over the blocks that move (not fixed or prescribed) and the stiffest spring a contact can
/// get (analysis.penalty, or a joint set's own normal stiffness). Zero period when nothing moves.
ContactPeriod shortest_contact_period(const Engine& engine, double dt);

}  // namespace ddafrac::dda
