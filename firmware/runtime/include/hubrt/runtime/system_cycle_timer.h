// The real-time CycleTimer: a timerfd armed at an absolute CLOCK_MONOTONIC deadline (so lateness
// never shifts later deadlines), an eventfd for wakes and stop requests, and a signalfd for the
// stop signals (stop_signals()), all waited on with one epoll set. A periodic cycle costs two
// system calls: arming the timerfd and epoll_wait (the timerfd is never read: arming clears it).
#pragma once

#include <csignal>
#include <memory>

#include "hubrt/runtime/cycle_timer.h"

namespace hubrt::runtime {

// The signals the system timer turns into a clean stop: every signal whose default action
// terminates the process (signal(7)) and that another process or the kernel sends asynchronously —
// SIGHUP, SIGINT, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGTERM, SIGSTKFLT, SIGVTALRM, SIGPROF,
// SIGIO, SIGPWR, SIGXCPU, SIGXFSZ and the real-time signals SIGRTMIN..SIGRTMAX. Left out on
// purpose: SIGKILL/SIGSTOP (cannot be caught), SIGPIPE (a program that must not die of a closed
// pipe ignores it, so that the write fails with EPIPE instead), and the faults a thread raises on
// itself (SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT, SIGTRAP, SIGSYS): a blocked synchronous fault
// is fatal at once without running any handler (kernel force_sig_fault), so they stay unblocked
// for a crash handler.
sigset_t stop_signals() noexcept;

class SystemCycleTimer final : public CycleTimer {
 public:
  // Blocks stop_signals() for the calling thread — call it before starting any other thread
  // (DDS participants) so that they inherit the mask, or such a signal could be delivered to a
  // thread that still has its default action, ending the process at once — and opens the timer,
  // event and signal fds. Errors: kIo with the failing system call named.
  static Expected<std::unique_ptr<SystemCycleTimer>> create();
  ~SystemCycleTimer() override;

  // `deadline` is on CLOCK_MONOTONIC (SystemClock's `mono`).
  Expected<TimerEvents> wait_until(Time deadline) override;
  void wake() const noexcept override;
  void request_stop() const noexcept override;

 private:
  SystemCycleTimer() noexcept = default;

  int timer_fd_ = -1;
  int event_fd_ = -1;
  int signal_fd_ = -1;
  int epoll_fd_ = -1;  // timer_fd_, event_fd_ and signal_fd_, registered once
  Time armed_{};       // the deadline the timerfd is armed at (re-armed only when it changes)
  bool is_armed_ = false;
};

}  // namespace hubrt::runtime
