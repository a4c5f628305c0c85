// Runs a Hub: periodic cycles on absolute deadlines (deadline k = start + k·period, so lateness
// never accumulates into drift), command steps as soon as a transport calls wake(), and a clean
// stop on request or on a stop signal (so no handler runs inside the cycle and the caller gets to
// drive its outputs safe before it exits). The waiting itself is a CycleTimer's: the system one
// (timerfd/eventfd/signalfd, see system_cycle_timer.h) in hubd, ManualCycleTimer in tests.
#pragma once

#include <functional>
#include <memory>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/runtime/cycle_timer.h"
#include "hubrt/runtime/hub.h"
#include "hubrt/runtime/stage_trace.h"
#include "hubrt/runtime/system_cycle_timer.h"

namespace hubrt::runtime {

// Wakes a CycleRunner from any thread. Async-signal-safe and allocation-free (the system timer's
// wake is one write(2)). Valid while the runner it came from lives.
class Waker {
 public:
  Waker() = default;
  explicit Waker(const CycleTimer* timer, StageTrace* trace = nullptr) noexcept
      : timer_(timer), trace_(trace) {}
  void wake() const noexcept {
    if (trace_ != nullptr) trace_->note_wake();
    if (timer_ != nullptr) timer_->wake();
  }

 private:
  const CycleTimer* timer_ = nullptr;
  StageTrace* trace_ = nullptr;  // stamps the wake when the hub's stages are traced
};

struct RunHooks {
  // After each periodic cycle (e.g. systemd watchdog ping, diagnostics). Must not block.
  std::function<void(const Instant&)> after_cycle;
};

enum class StopReason : std::uint8_t { kSignal, kRequested };

class CycleRunner {
 public:
  // The real-time runner over SystemCycleTimer::create() — which blocks stop_signals() for the
  // calling thread: call it before starting any other thread (DDS participants).
  // Errors: kIo with the failing system call named.
  static Expected<CycleRunner> create();
  // A runner over `timer` (e.g. a ManualCycleTimer). Precondition: timer is not null.
  explicit CycleRunner(std::unique_ptr<CycleTimer> timer) noexcept;
  CycleRunner(CycleRunner&& other) noexcept = default;
  CycleRunner& operator=(CycleRunner&&) = delete;
  CycleRunner(const CycleRunner&) = delete;
  ~CycleRunner() = default;

  [[nodiscard]] Waker waker() const noexcept { return Waker(timer_.get(), trace_); }
  // Stamps every command step's stages into `trace` (stage_trace.h; null: none, the default);
  // call before waker() is handed out, so that its wakes are stamped too. `trace` must outlive
  // the runner's runs; run() also hands it to the hub.
  void trace_stages(StageTrace* trace) noexcept { trace_ = trace; }
  // Asks run() to return after the current step. Thread-safe.
  void request_stop() const noexcept { timer_->request_stop(); }

  // Runs cycles every hub.options().period until a stop signal or request_stop(). The first cycle
  // runs at once (at start = clock.now()); cycle k is due at start + k·period whatever the earlier
  // cycles took. When a step ran past one or more further deadlines, those deadlines count as
  // overruns in hub.stats() and ONE cycle runs at once, then the schedule goes on at the next
  // deadline still ahead (no burst of catch-up cycles). When the runner comes back more than a
  // period after a deadline (the process was stopped or paused, a step blocked), it tells the hub
  // first (Hub::note_late), before any step takes a command. A wake runs a command step at
  // clock.now() between cycles. `clock` reads the time the timer waits on (SystemClock for
  // create(), the ManualClock of a ManualCycleTimer).
  // Errors: kInvalidArgument for a non-positive period; kIo for a failing system call.
  Expected<StopReason> run(Hub& hub, const Clock& clock, const RunHooks& hooks = {});
  // The signal that ended the last run() (one of stop_signals()), 0 if none did.
  [[nodiscard]] int last_signal() const noexcept { return last_signal_; }

 private:
  std::unique_ptr<CycleTimer> timer_;
  StageTrace* trace_ = nullptr;
  int last_signal_ = 0;
};

}  // namespace hubrt::runtime
