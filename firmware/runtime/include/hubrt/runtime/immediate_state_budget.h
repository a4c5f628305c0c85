// How often a node may publish its State *at once* — outside the heartbeat — because a command
// took effect. Without a bound, a planner (or two) flipping its command thousands of times a
// second makes the hub publish thousands of States a second (issue 11: 5,420 States/s from one
// hub) and floods the network for every other hub.
//
// The rule (README, "The wire contract"): a token bucket per node. It holds at most `burst`
// immediate States and refills at one per `min_interval`; each immediate State takes one. So a
// command after a quiet period — and up to `burst` commands back to back — is echoed at once,
// while a flood gets at most `burst` + t / `min_interval` immediate States over any span t (100/s
// at the default 10 ms). A change that takes effect while the bucket is empty is not lost — the
// command still takes effect at once (the outputs follow it) and the latest one wins — only its
// State waits: it goes out with the next State, i.e. the first command step once a token is back
// or the next heartbeat, whichever comes first. The heartbeat is never held back and takes no
// token. A planner that commands every 20–120 ms never notices.
//
// Issue 16 replaced a plain minimum interval (one immediate State per `min_interval`, no burst):
// that held back every second command of a planner commanding back to back, so the echo of a
// command sent right after the previous echo waited for the heartbeat (p50 8.9 ms against
// 0.08 ms before the budget).
//
// The bucket is kept as a "theoretical arrival time" (the generic cell rate algorithm, ITU-T
// I.371): `due_` is when the bucket would be empty-and-refilled if every token taken so far had
// been spaced `min_interval` apart; a State may go at `now` when now >= due_ - (burst-1) *
// min_interval. Integer nanoseconds, no drift, no floating point.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdint>

#include "hubrt/base/time.h"

namespace hubrt::runtime {

// Default of `immediate_state_interval_ms` in the hub file: the bucket's refill period. Well
// below the fastest well-behaved planner's command period (20 ms), and a cap of 100 immediate
// States/s per node against a flooding one.
inline constexpr Duration kDefaultImmediateStateInterval = std::chrono::milliseconds(10);
// Immediate States a node may publish back to back after a quiet period: a command, its
// follow-up and a new reader's State all answered at once, while a flood of 1 s gets at most
// 4 more than the 100 the refill allows.
inline constexpr std::uint32_t kDefaultImmediateStateBurst = 4;

// Deterministic (time passed in), allocation-free. Not thread-safe: the cycle thread's.
class ImmediateStateBudget {
 public:
  // A zero `min_interval` allows every immediate State (no budget). `burst` below 1 counts as 1.
  explicit ImmediateStateBudget(Duration min_interval = kDefaultImmediateStateInterval,
                                std::uint32_t burst = kDefaultImmediateStateBurst) noexcept
      : min_interval_(min_interval), burst_(std::max<std::uint32_t>(burst, 1)) {}

  // A step between heartbeats at `now`; `took_effect`: a command took effect in it. True when the
  // State must be published now (a change now, or one held back earlier, and a token is there);
  // the caller then publishes. A change while the bucket is empty is held back and counted.
  bool publish_now(Time now, bool took_effect) noexcept {
    if (!took_effect && !held_back_) return false;
    if (!take_token(now)) {
      if (took_effect) ++deferred_;
      held_back_ = true;
      return false;
    }
    held_back_ = false;
    return true;
  }
  // The heartbeat published the State: whatever was held back went out with it.
  void on_heartbeat() noexcept { held_back_ = false; }

  [[nodiscard]] Duration min_interval() const noexcept { return min_interval_; }
  [[nodiscard]] std::uint32_t burst() const noexcept { return burst_; }
  // A change is waiting for the next State.
  [[nodiscard]] bool held_back() const noexcept { return held_back_; }
  // Changes whose immediate State was held back, since construction.
  [[nodiscard]] std::uint64_t deferred() const noexcept { return deferred_; }

 private:
  bool take_token(Time now) noexcept {
    if (min_interval_ <= Duration::zero()) return true;
    // Unused tokens never exceed the burst: an idle bucket starts from `now`.
    const Time from = has_taken_ ? std::max(due_, now) : now;
    if (has_taken_ && now < due_ - (burst_ - 1) * min_interval_) return false;
    due_ = from + min_interval_;
    has_taken_ = true;
    return true;
  }

  Duration min_interval_;
  std::uint32_t burst_;
  Time due_{};
  bool has_taken_ = false;
  bool held_back_ = false;
  std::uint64_t deferred_ = 0;
};

}  // namespace hubrt::runtime
