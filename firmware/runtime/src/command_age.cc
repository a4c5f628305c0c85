#include "hubrt/runtime/command_age.h"

namespace hubrt::runtime {

JudgedAge CommandAgeJudge::judge(const CommandTimes& times) noexcept {
  JudgedAge judged;
  judged.written = times.taken.mono;
  const bool stamped = times.source.has_value() && times.source->ns_since_epoch > 0;
  if (stamped) {
    const WallTime hub_wall = times.take_wall.value_or(times.taken.wall);
    judged.offset = Duration(hub_wall.ns_since_epoch - times.source->ns_since_epoch);
    offset_seen_ = true;
    last_offset_ = judged.offset;
    const auto magnitude = [](Duration d) { return d < Duration::zero() ? -d : d; };
    if (magnitude(judged.offset) > magnitude(largest_offset_)) largest_offset_ = judged.offset;
  }
  // What queued while the hub could not run is dropped whatever its stamp says: with unsynced
  // clocks the stamp says nothing, and with synced ones this only adds the settle window.
  if (discarding(times.taken.mono)) {
    judged.verdict = AgeVerdict::kQueued;
    return judged;
  }
  // In-process commands (no stamp at all) and unsynced clocks: as old as the arrival.
  if (!times.source.has_value() || !tolerance_.has_value()) return judged;
  if (!stamped) {
    judged.verdict = AgeVerdict::kUnstamped;
    return judged;
  }
  if (judged.offset < -*tolerance_) {
    judged.verdict = AgeVerdict::kFuture;
    return judged;
  }
  const Duration age = judged.offset > Duration::zero() ? judged.offset : Duration::zero();
  if (age > timeout_) {
    judged.verdict = AgeVerdict::kStale;
    return judged;
  }
  judged.written = times.taken.mono - age;
  return judged;
}

}  // namespace hubrt::runtime
