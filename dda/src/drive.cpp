#include "ddafrac/dda/drive.hpp"

namespace ddafrac::dda {

DriveEnd drive(Engine& engine, double until, const DriveHooks& hooks) {
  for (;;) {
    if (hooks.interrupt && hooks.interrupt() == Next::Stop) return DriveEnd::Stopped;
    if (reached(engine.time(), until)) return DriveEnd::Reached;
    if (hooks.before_step && hooks.before_step() == Next::Stop) return DriveEnd::Stopped;
    const double land = hooks.land_at ? hooks.land_at() : until;
    const StepReport report = engine.step(land - engine.time());
    if (hooks.after_step && hooks.after_step(report) == Next::Stop) return DriveEnd::Stopped;
  }
}

}  // namespace ddafrac::dda
