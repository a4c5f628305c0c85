#include "hubrt/runtime/command_tracker.h"

namespace hubrt::runtime {

CommandTracker::Arrival CommandTracker::on_valid_command(Time now, Time written, bool differs,
                                                         bool is_reset) noexcept {
  last_taken_ = now;
  // The youngest command known feeds the watchdog: one that was written earlier than a command
  // already seen (another writer's, delayed) cannot make the node's freshness shorter.
  if (!has_echo_ || !in_force_ || written > last_written_) last_written_ = written;
  const bool takes_effect = differs || !in_force_;
  has_echo_ = true;
  in_force_ = true;
  if (!takes_effect) return Arrival::kRepeat;
  took_effect_ = written;
  reset_in_force_ = is_reset;
  return Arrival::kTookEffect;
}

CommandTracker::Watchdog CommandTracker::check(Time now) noexcept {
  if (in_force_ && now - last_written_ > timeout_) {
    in_force_ = false;
    return Watchdog::kTripped;
  }
  return Watchdog::kQuiet;
}

double CommandTracker::t_plus(Time now) const noexcept {
  if (!has_echo_) return 0.0;
  return to_seconds(now - took_effect_);
}

}  // namespace hubrt::runtime
