#include "hubrt/runtime/manual_cycle_timer.h"

#include <algorithm>

namespace hubrt::runtime {

void ManualCycleTimer::schedule(const Scheduled& event) {
  // After every event at the same instant: events at one instant happen in the order scheduled.
  const auto later = std::upper_bound(scheduled_.begin(), scheduled_.end(), event.at,
                                      [](Time at, const Scheduled& other) { return at < other.at; });
  scheduled_.insert(later, event);
}

void ManualCycleTimer::wake_at(Time at) {
  schedule(Scheduled{at, true, false, 0});
}

void ManualCycleTimer::request_stop_at(Time at) {
  schedule(Scheduled{at, false, true, 0});
}

void ManualCycleTimer::signal_at(Time at, int signal) {
  schedule(Scheduled{at, false, false, signal});
}

void ManualCycleTimer::pause_at(Time at, Duration length) {
  schedule(Scheduled{at, false, false, 0, length});
}

Expected<TimerEvents> ManualCycleTimer::wait_until(Time deadline) {
  ++waits_;
  Time now = clock_.now().mono;
  const bool pending =
      woken_.load() || stop_requested_.load() || (!scheduled_.empty() && scheduled_.front().at <= now);
  if (!pending) {
    // Sleeping until the earlier of the deadline and the next scheduled event.
    const Time until = scheduled_.empty() ? deadline : std::min(deadline, scheduled_.front().at);
    if (until > now) {
      clock_.set(until);
      now = until;
    }
  }
  TimerEvents events;
  while (!scheduled_.empty() && scheduled_.front().at <= now) {
    const Scheduled& event = scheduled_.front();
    if (event.pause > Duration::zero()) {  // time passes without this process running
      clock_.advance(event.pause);
      now += event.pause;
    }
    if (event.wake) woken_.store(true);
    if (event.stop) stop_requested_.store(true);
    if (event.signal != 0 && events.stop_signal == 0) events.stop_signal = event.signal;
    scheduled_.erase(scheduled_.begin());
  }
  events.woken = woken_.exchange(false);
  events.stop_requested = stop_requested_.exchange(false);
  events.deadline_reached = now >= deadline;
  return events;
}

}  // namespace hubrt::runtime
