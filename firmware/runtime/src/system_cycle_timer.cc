#include "hubrt/runtime/system_cycle_timer.h"

#include <poll.h>
#include <pthread.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <memory>
#include <system_error>

#include <fmt/format.h>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>

namespace hubrt::runtime {
namespace {

// Marks a stop request in the event counter, distinct from ordinary wakes (which add 1).
constexpr std::uint64_t kStopIncrement = std::uint64_t{1} << 40;

Error system_error(const char* what) {
  return make_error(ErrorCode::kIo,
                    fmt::format("{} failed: {}", what, std::generic_category().message(errno)));
}

timespec to_timespec(Duration d) {
  const auto ns = d.count();
  return timespec{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
}

void close_fd(int& fd) noexcept {
  if (fd >= 0) ::close(fd);
  fd = -1;
}

}  // namespace

sigset_t stop_signals() noexcept {
  sigset_t signals;
  sigemptyset(&signals);
  for (const int signal : {SIGHUP, SIGINT, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM, SIGTERM, SIGSTKFLT, SIGVTALRM,
                           SIGPROF, SIGIO, SIGPWR, SIGXCPU, SIGXFSZ}) {
    sigaddset(&signals, signal);
  }
  // SIGRTMIN is a function call in glibc: it leaves out the real-time signals the C library keeps
  // for itself (thread cancellation, setxid), which must stay unblocked.
  for (int signal = SIGRTMIN; signal <= SIGRTMAX; ++signal) sigaddset(&signals, signal);
  return signals;
}

Expected<std::unique_ptr<SystemCycleTimer>> SystemCycleTimer::create() {
  const sigset_t signals = stop_signals();
  if (pthread_sigmask(SIG_BLOCK, &signals, nullptr) != 0) return system_error("pthread_sigmask");
  const int signal_fd = signalfd(-1, &signals, SFD_CLOEXEC | SFD_NONBLOCK);
  if (signal_fd < 0) return system_error("signalfd");
  const int timer_fd = timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC | TFD_NONBLOCK);
  if (timer_fd < 0) {
    ::close(signal_fd);
    return system_error("timerfd_create");
  }
  const int event_fd = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (event_fd < 0) {
    ::close(signal_fd);
    ::close(timer_fd);
    return system_error("eventfd");
  }
  return std::unique_ptr<SystemCycleTimer>(new SystemCycleTimer(timer_fd, event_fd, signal_fd));
}

SystemCycleTimer::SystemCycleTimer(int timer_fd, int event_fd, int signal_fd) noexcept
    : timer_fd_(timer_fd), event_fd_(event_fd), signal_fd_(signal_fd) {}

SystemCycleTimer::~SystemCycleTimer() {
  close_fd(timer_fd_);
  close_fd(event_fd_);
  close_fd(signal_fd_);
}

void SystemCycleTimer::wake() const noexcept {
  const std::uint64_t one = 1;
  // A full counter (never in practice) only means a wake is already pending.
  [[maybe_unused]] const ssize_t n = ::write(event_fd_, &one, sizeof one);
}

void SystemCycleTimer::request_stop() const noexcept {
  const std::uint64_t stop = kStopIncrement;
  [[maybe_unused]] const ssize_t n = ::write(event_fd_, &stop, sizeof stop);
}

Expected<TimerEvents> SystemCycleTimer::wait_until(Time deadline) {
  if (!is_armed_ || deadline != armed_) {
    // One-shot at an absolute time (TFD_TIMER_ABSTIME): a deadline already past fires at once
    // (timerfd_create(2)); an all-zero it_value would disarm instead, hence at least 1 ns.
    itimerspec spec{};
    spec.it_value = to_timespec(deadline.time_since_epoch());
    if (spec.it_value.tv_sec == 0 && spec.it_value.tv_nsec == 0) spec.it_value.tv_nsec = 1;
    if (timerfd_settime(timer_fd_, TFD_TIMER_ABSTIME, &spec, nullptr) != 0)
      return system_error("timerfd_settime");
    armed_ = deadline;
    is_armed_ = true;
  }
  std::array<pollfd, 3> fds{{{timer_fd_, POLLIN, 0}, {event_fd_, POLLIN, 0}, {signal_fd_, POLLIN, 0}}};
  for (;;) {
    const int ready = ::poll(fds.data(), fds.size(), -1);
    if (ready >= 0) break;
    if (errno != EINTR) return system_error("poll");
  }
  TimerEvents events;
  if ((fds[2].revents & POLLIN) != 0) {
    signalfd_siginfo info{};
    if (::read(signal_fd_, &info, sizeof info) == sizeof info) {
      // A stop signal ends the run: the other fds are left unread, as nothing reads them after.
      events.stop_signal = static_cast<int>(info.ssi_signo);
      return events;
    }
  }
  if ((fds[1].revents & POLLIN) != 0) {
    std::uint64_t count = 0;
    if (::read(event_fd_, &count, sizeof count) == sizeof count) {
      events.stop_requested = count >= kStopIncrement;
      events.woken = count % kStopIncrement != 0;
    }
  }
  if ((fds[0].revents & POLLIN) != 0) {
    std::uint64_t expirations = 0;
    events.deadline_reached =
        ::read(timer_fd_, &expirations, sizeof expirations) == sizeof expirations && expirations > 0;
    // A one-shot timer that fired stays disarmed: the next wait arms it again even for the
    // same deadline.
    if (events.deadline_reached) is_armed_ = false;
  }
  return events;
}

}  // namespace hubrt::runtime
