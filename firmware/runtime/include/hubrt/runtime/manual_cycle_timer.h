// A CycleTimer for tests: waiting moves a ManualClock to the deadline instead of sleeping, and
// wakes, stop requests and stop signals happen at scheduled instants. With it, CycleRunner's
// schedule (absolute deadlines, overrun counting, command steps between cycles) is tested
// deterministically, in one thread, without real time passing. A node's step that "takes long"
// advances the same ManualClock.
#pragma once

#include <atomic>
#include <vector>

#include "hubrt/runtime/cycle_timer.h"

namespace hubrt::runtime {

class ManualCycleTimer final : public CycleTimer {
 public:
  explicit ManualCycleTimer(ManualClock& clock) noexcept : clock_(clock) {}

  // Schedules an event at `at` (on the ManualClock): a wait whose deadline lies after `at` ends
  // there with the clock at `at`. Events scheduled in the past happen on the next wait. Not
  // thread-safe: schedule from the thread that runs the runner, before or between waits.
  void wake_at(Time at);
  void request_stop_at(Time at);
  void signal_at(Time at, int signal);
  // The process is stopped at `at` for `length` (SIGSTOP and SIGCONT, a VM pause): a wait that
  // would sleep past `at` comes back at `at + length`, its deadline long gone.
  void pause_at(Time at, Duration length);

  // Waits "until" the earlier of `deadline` and the next scheduled event by setting the clock
  // there; an event already pending (wake(), request_stop(), or scheduled at or before now) ends
  // the wait without moving the clock. Never fails.
  Expected<TimerEvents> wait_until(Time deadline) override;
  void wake() const noexcept override { woken_.store(true); }
  void request_stop() const noexcept override { stop_requested_.store(true); }

  // Waits so far (how often the runner came back to wait).
  [[nodiscard]] std::uint64_t waits() const noexcept { return waits_; }

 private:
  struct Scheduled {
    Time at;
    bool wake = false;
    bool stop = false;
    int signal = 0;
    Duration pause{0};
  };
  void schedule(const Scheduled& event);

  ManualClock& clock_;
  std::vector<Scheduled> scheduled_;  // sorted by `at`
  mutable std::atomic<bool> woken_{false};
  mutable std::atomic<bool> stop_requested_{false};
  std::uint64_t waits_ = 0;
};

}  // namespace hubrt::runtime
