#pragma once
// The one time loop: steps an Engine towards an end time, one accepted step at a time, and lets
// the caller look at every step through hooks. The run, the bench, the stability study and the
// verification twins all drive their engine with it, so they agree on when an end time counts as
// reached. Nothing here writes a file: what a caller records is its own hooks' business.

#include <functional>

#include "ddafrac/dda/engine.hpp"

namespace ddafrac::dda {

/// Slack on simulated times, as a share of the time compared against (dimensionless). The last
/// step is shortened to land on the end time, but the sum of the steps meets it only up to
/// rounding: the end time counts as reached once the engine is within this share of it.
inline constexpr double kTimeSlack = 1e-9;

/// True once `time` (s) has reached `end` (s) up to kTimeSlack·end.
inline bool reached(double time, double end) { return time >= end * (1.0 - kTimeSlack); }

/// What a hook tells the driver.
enum class Next { Continue, Stop };

/// Why drive() returned.
enum class DriveEnd { Reached, Stopped };

/// The caller's view of the loop; every hook is optional.
struct DriveHooks {
  /// Before each step, ahead of the end-time test: Stop ends the drive even at the end time (a
  /// stop request or a step budget that must win over a finished run).
  std::function<Next()> interrupt;
  /// Before each step the end time still leaves to take: Stop ends the drive (a step or wall
  /// budget); also the place to change the OpenMP thread count between steps.
  std::function<Next()> before_step;
  /// The time the next step must not pass (s), e.g. the next output time; the end time without it.
  std::function<double()> land_at;
  /// After each accepted step, with its report: Stop ends the drive.
  std::function<Next(const StepReport&)> after_step;
};

/// Steps `engine` until its time has reached `until` (s; +infinity steps until a hook stops it),
/// each step no longer than what is left to the landing time. Exceptions of Engine::step
/// (NumericalTrouble) and of the hooks pass through.
DriveEnd drive(Engine& engine, double until, const DriveHooks& hooks);

}  // namespace ddafrac::dda
