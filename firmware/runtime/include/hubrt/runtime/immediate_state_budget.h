// How often a node may publish its State *at once* — outside the heartbeat — because a command
// took effect. Without a bound, a planner (or two) flipping its command thousands of times a
// second makes the hub publish thousands of States a second (issue 11: 5,420 States/s from one
// hub) and floods the network for every other hub.
//
// The rule (README, "The wire contract"): at most one immediate State per node per
// `min_interval`. A change that takes effect inside that window is not lost — the command still
// takes effect at once (the outputs follow it) and the latest one wins — only its State waits:
// it goes out with the next State, i.e. the first command step after the window or the next
// heartbeat, whichever comes first. The heartbeat is never held back and does not count.
// A planner that commands every 20–120 ms never notices: the first change after at least
// `min_interval` of quiet always publishes at once.
#pragma once

#include <chrono>
#include <cstdint>

#include "hubrt/base/time.h"

namespace hubrt::runtime {

// Default of `immediate_state_interval_ms` in the hub file: well below the fastest well-behaved
// planner's command period (20 ms, so even two of its commands bunched up by delivery jitter to
// half their spacing both publish at once), and a cap of 100 immediate States/s per node against
// a flooding one.
inline constexpr Duration kDefaultImmediateStateInterval = std::chrono::milliseconds(10);

// Deterministic (time passed in), allocation-free. Not thread-safe: the cycle thread's.
class ImmediateStateBudget {
 public:
  // A zero `min_interval` allows every immediate State (no budget).
  explicit ImmediateStateBudget(Duration min_interval = kDefaultImmediateStateInterval) noexcept
      : min_interval_(min_interval) {}

  // A step between heartbeats at `now`; `took_effect`: a command took effect in it. True when the
  // State must be published now (a change now, or one held back earlier, and the window is
  // open); the caller then publishes. A change inside the window is held back and counted.
  bool publish_now(Time now, bool took_effect) noexcept {
    if (!took_effect && !held_back_) return false;
    if (has_published_ && now - last_immediate_ < min_interval_) {
      if (took_effect) ++deferred_;
      held_back_ = true;
      return false;
    }
    has_published_ = true;
    last_immediate_ = now;
    held_back_ = false;
    return true;
  }
  // The heartbeat published the State: whatever was held back went out with it.
  void on_heartbeat() noexcept { held_back_ = false; }

  [[nodiscard]] Duration min_interval() const noexcept { return min_interval_; }
  // A change is waiting for the next State.
  [[nodiscard]] bool held_back() const noexcept { return held_back_; }
  // Changes whose immediate State was held back, since construction.
  [[nodiscard]] std::uint64_t deferred() const noexcept { return deferred_; }

 private:
  Duration min_interval_;
  Time last_immediate_{};
  bool has_published_ = false;
  bool held_back_ = false;
  std::uint64_t deferred_ = 0;
};

}  // namespace hubrt::runtime
