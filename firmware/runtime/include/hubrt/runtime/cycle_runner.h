// Runs a Hub in real time: periodic cycles on absolute deadlines of CLOCK_MONOTONIC (a timerfd, so
// lateness never accumulates into drift), command steps as soon as a transport calls wake(), and a
// clean stop on every signal whose default action ends the process and that can be blocked
// (stop_signals(): read from a signalfd, so no handler runs inside the cycle and the caller gets
// to drive its outputs safe before it exits).
#pragma once

#include <csignal>
#include <functional>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/runtime/hub.h"

namespace hubrt::runtime {

// Wakes a CycleRunner from any thread. Async-signal-safe and allocation-free (one write(2)).
class Waker {
 public:
  Waker() = default;
  explicit Waker(int event_fd) noexcept : fd_(event_fd) {}
  void wake() const noexcept;

 private:
  int fd_ = -1;
};

struct RunHooks {
  // After each periodic cycle (e.g. systemd watchdog ping, diagnostics). Must not block.
  std::function<void(const Instant&)> after_cycle;
};

enum class StopReason : std::uint8_t { kSignal, kRequested };

// The signals CycleRunner turns into a clean stop: every signal whose default action terminates
// the process (signal(7)) and that another process or the kernel sends asynchronously — SIGHUP,
// SIGINT, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGTERM, SIGSTKFLT, SIGVTALRM, SIGPROF, SIGIO,
// SIGPWR, SIGXCPU, SIGXFSZ and the real-time signals SIGRTMIN..SIGRTMAX. Left out on purpose:
// SIGKILL/SIGSTOP (cannot be caught), SIGPIPE (a program that must not die of a closed pipe
// ignores it, so that the write fails with EPIPE instead), and the faults a thread raises on itself
// (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS): a blocked synchronous fault is
// fatal at once without running any handler (kernel force_sig_fault), so they stay unblocked for a
// crash handler.
sigset_t stop_signals() noexcept;

class CycleRunner {
 public:
  // Blocks stop_signals() for the calling thread — call it before starting any other thread
  // (DDS participants) so that they inherit the mask, or such a signal could be delivered to a
  // thread that still has its default action, ending the process at once — and opens the timer,
  // event and signal fds.
  // Errors: kIo with the failing system call named.
  static Expected<CycleRunner> create();
  CycleRunner(CycleRunner&& other) noexcept;
  CycleRunner& operator=(CycleRunner&&) = delete;
  CycleRunner(const CycleRunner&) = delete;
  ~CycleRunner();

  [[nodiscard]] Waker waker() const noexcept { return Waker(event_fd_); }
  // Asks run() to return after the current step. Thread-safe.
  void request_stop() const noexcept;

  // Runs cycles every hub.options().period until a signal or request_stop(). The first cycle runs
  // at once. Each periodic deadline missed while a cycle ran late counts as an overrun in
  // hub.stats(). Errors: kInvalidArgument for a non-positive period; kIo for a failing system call.
  Expected<StopReason> run(Hub& hub, const Clock& clock, const RunHooks& hooks = {});
  // The signal that ended the last run() (one of stop_signals()), 0 if none did.
  [[nodiscard]] int last_signal() const noexcept { return last_signal_; }

 private:
  CycleRunner(int timer_fd, int event_fd, int signal_fd) noexcept;

  int timer_fd_ = -1;
  int event_fd_ = -1;
  int signal_fd_ = -1;
  int last_signal_ = 0;
};

}  // namespace hubrt::runtime
