#include "hubrt/runtime/cycle_runner.h"

#include <utility>

namespace hubrt::runtime {

Expected<CycleRunner> CycleRunner::create() {
  auto timer = SystemCycleTimer::create();
  if (!timer) return timer.error();
  return CycleRunner(std::move(*timer));
}

CycleRunner::CycleRunner(std::unique_ptr<CycleTimer> timer) noexcept : timer_(std::move(timer)) {}

Expected<StopReason> CycleRunner::run(Hub& hub, const Clock& clock, const RunHooks& hooks) {
  const Duration period = hub.options().period;
  if (period <= Duration::zero())
    return make_error(ErrorCode::kInvalidArgument, "cycle period must be positive");
  // Absolute periodic schedule: the next deadline only ever moves by whole periods from the start,
  // independent of when we wake.
  Time next = clock.now().mono;
  hub.trace_stages(trace_);
  for (;;) {
    auto events = timer_->wait_until(next);
    if (!events) return events.error();
    if (events->stop_signal != 0) {
      last_signal_ = events->stop_signal;
      return StopReason::kSignal;
    }
    if (events->stop_requested) return StopReason::kRequested;
    // Held past a deadline by more than a period: stopped (SIGSTOP), paused (a VM), or a step that
    // blocked. The nodes drop what queued meanwhile before any step can take it.
    const Instant woke = clock.now();
    if (woke.mono - next > period) hub.note_late(woke, woke.mono - next);
    if (events->woken) {
      if (trace_ != nullptr) trace_->begin_step(woke.mono);
      hub.command_step(woke);
      if (trace_ != nullptr) trace_->end_step();
    }
    if (!events->deadline_reached) continue;
    // One reading of the clock per step, as before the stall check: a fresh one after a command step.
    const Instant now = events->woken ? clock.now() : woke;
    // Deadlines after `next` that have passed too were missed: counted, not run.
    const std::int64_t missed = now.mono > next ? (now.mono - next) / period : 0;
    hub.count_overruns(static_cast<std::uint64_t>(missed));
    next += (missed + 1) * period;
    hub.cycle(now);
    if (hooks.after_cycle) hooks.after_cycle(now);
  }
}

}  // namespace hubrt::runtime
