#include "hubrt/runtime/system_cycle_timer.h"

#include <pthread.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <memory>
#include <system_error>
#include <utility>

#include <fmt/format.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/signalfd.h>
#include <sys/timerfd.h>

namespace hubrt::runtime {
namespace {

// Marks a stop request in the event counter, distinct from ordinary wakes (which add 1).
constexpr std::uint64_t kStopIncrement = std::uint64_t{1} << 40;

// What each fd is registered as in the epoll set (epoll_event.data.u32).
enum FdTag : std::uint32_t { kTimerTag = 0, kEventTag = 1, kSignalTag = 2 };

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
  // Owned by the timer as soon as it exists, so every early return below closes what was opened.
  std::unique_ptr<SystemCycleTimer> timer(new SystemCycleTimer());
  timer->signal_fd_ = signalfd(-1, &signals, SFD_CLOEXEC | SFD_NONBLOCK);
  if (timer->signal_fd_ < 0) return system_error("signalfd");
  timer->timer_fd_ = timerfd_create(CLOCK_MONOTONIC, TFD_CLOEXEC | TFD_NONBLOCK);
  if (timer->timer_fd_ < 0) return system_error("timerfd_create");
  timer->event_fd_ = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  if (timer->event_fd_ < 0) return system_error("eventfd");
  // One epoll set registered once, instead of poll(2) handing the kernel the three fds (and
  // hooking the thread onto their three wait queues and off again) at every wait.
  timer->epoll_fd_ = epoll_create1(EPOLL_CLOEXEC);
  if (timer->epoll_fd_ < 0) return system_error("epoll_create1");
  for (const auto& [fd, tag] :
       {std::pair{timer->timer_fd_, kTimerTag}, std::pair{timer->event_fd_, kEventTag},
        std::pair{timer->signal_fd_, kSignalTag}}) {
    epoll_event event{};
    event.events = EPOLLIN;
    event.data.u32 = tag;
    if (epoll_ctl(timer->epoll_fd_, EPOLL_CTL_ADD, fd, &event) != 0) return system_error("epoll_ctl");
  }
  return timer;
}

SystemCycleTimer::~SystemCycleTimer() {
  close_fd(timer_fd_);
  close_fd(event_fd_);
  close_fd(signal_fd_);
  close_fd(epoll_fd_);
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
    // Arming also clears an expiration not read (Linux fs/timerfd.c, timerfd_setup() zeroes the
    // tick count): the timerfd is readable again only once this deadline has come, so a
    // readable timerfd is all the wait needs to know and it is never read — one system call per
    // cycle less than reading the expiration count.
    itimerspec spec{};
    spec.it_value = to_timespec(deadline.time_since_epoch());
    if (spec.it_value.tv_sec == 0 && spec.it_value.tv_nsec == 0) spec.it_value.tv_nsec = 1;
    if (timerfd_settime(timer_fd_, TFD_TIMER_ABSTIME, &spec, nullptr) != 0)
      return system_error("timerfd_settime");
    armed_ = deadline;
    is_armed_ = true;
  }
  std::array<epoll_event, 3> ready{};
  int count = 0;
  for (;;) {
    count = epoll_wait(epoll_fd_, ready.data(), static_cast<int>(ready.size()), -1);
    if (count >= 0) break;
    if (errno != EINTR) return system_error("epoll_wait");
  }
  bool timer_ready = false;
  bool event_ready = false;
  bool signal_ready = false;
  for (int i = 0; i < count; ++i) {
    if ((ready[static_cast<std::size_t>(i)].events & EPOLLIN) == 0) continue;
    const std::uint32_t tag = ready[static_cast<std::size_t>(i)].data.u32;
    timer_ready |= tag == kTimerTag;
    event_ready |= tag == kEventTag;
    signal_ready |= tag == kSignalTag;
  }
  TimerEvents events;
  if (signal_ready) {
    signalfd_siginfo info{};
    if (::read(signal_fd_, &info, sizeof info) == sizeof info) {
      // A stop signal ends the run: the other fds are left unread, as nothing reads them after.
      events.stop_signal = static_cast<int>(info.ssi_signo);
      return events;
    }
  }
  if (event_ready) {
    std::uint64_t count_read = 0;
    if (::read(event_fd_, &count_read, sizeof count_read) == sizeof count_read) {
      events.stop_requested = count_read >= kStopIncrement;
      events.woken = count_read % kStopIncrement != 0;
    }
  }
  if (timer_ready) {
    events.deadline_reached = true;
    // A one-shot timer that fired stays disarmed: the next wait arms it again even for the
    // same deadline, which also clears this expiration.
    is_armed_ = false;
  }
  return events;
}

}  // namespace hubrt::runtime
