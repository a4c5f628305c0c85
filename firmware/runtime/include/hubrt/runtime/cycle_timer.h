// What CycleRunner waits on: "until this absolute deadline, or until woken, asked to stop or sent
// a stop signal". The runner owns the schedule (deadline k = start + k·period, overrun counting);
// a timer only waits. SystemCycleTimer waits in real time (timerfd/eventfd/signalfd);
// ManualCycleTimer moves a ManualClock instead, so the runner's schedule is tested without time
// passing.
#pragma once

#include <cstdint>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::runtime {

// What ended one wait; several may be true at once.
struct TimerEvents {
  bool deadline_reached = false;  // the deadline waited for has come
  bool woken = false;             // wake() was called since the last wait
  bool stop_requested = false;    // request_stop() was called
  int stop_signal = 0;            // a stop signal arrived (its number), 0 if none
};

class CycleTimer {
 public:
  CycleTimer() = default;
  CycleTimer(const CycleTimer&) = delete;
  CycleTimer& operator=(const CycleTimer&) = delete;
  virtual ~CycleTimer() = default;

  // Blocks until `deadline` — absolute, on the clock CycleRunner::run() is given — has come or one
  // of the other events happened; returns at once if one is already pending. Call from one thread
  // (the cycle's). Errors: kIo for a failing system call.
  virtual Expected<TimerEvents> wait_until(Time deadline) = 0;
  // Ends the current or next wait with `woken`. Thread-safe, async-signal-safe, allocation-free.
  virtual void wake() const noexcept = 0;
  // Ends the current or next wait with `stop_requested`. Thread-safe, allocation-free.
  virtual void request_stop() const noexcept = 0;
};

}  // namespace hubrt::runtime
