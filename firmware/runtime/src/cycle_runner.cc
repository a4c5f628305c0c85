#include "hubrt/runtime/cycle_runner.h"

#include <poll.h>
#include <unistd.h>

#include <cerrno>
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

void Waker::wake() const noexcept {
  if (fd_ < 0) return;
  const std::uint64_t one = 1;
  // A full counter (never in practice) only means a wake is already pending.
  [[maybe_unused]] const ssize_t n = ::write(fd_, &one, sizeof one);
}

Expected<CycleRunner> CycleRunner::create() {
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
  return CycleRunner(timer_fd, event_fd, signal_fd);
}

CycleRunner::CycleRunner(int timer_fd, int event_fd, int signal_fd) noexcept
    : timer_fd_(timer_fd), event_fd_(event_fd), signal_fd_(signal_fd) {}

CycleRunner::CycleRunner(CycleRunner&& other) noexcept
    : timer_fd_(std::exchange(other.timer_fd_, -1)),
      event_fd_(std::exchange(other.event_fd_, -1)),
      signal_fd_(std::exchange(other.signal_fd_, -1)),
      last_signal_(other.last_signal_) {}

CycleRunner::~CycleRunner() {
  close_fd(timer_fd_);
  close_fd(event_fd_);
  close_fd(signal_fd_);
}

void CycleRunner::request_stop() const noexcept {
  const std::uint64_t stop = kStopIncrement;
  [[maybe_unused]] const ssize_t n = ::write(event_fd_, &stop, sizeof stop);
}

Expected<StopReason> CycleRunner::run(Hub& hub, const Clock& clock, const RunHooks& hooks) {
  const Duration period = hub.options().period;
  if (period <= Duration::zero())
    return make_error(ErrorCode::kInvalidArgument, "cycle period must be positive");
  // Absolute periodic schedule: deadline k = start + k * period, independent of when we wake.
  itimerspec spec{};
  spec.it_interval = to_timespec(period);
  timespec start{};
  clock_gettime(CLOCK_MONOTONIC, &start);
  spec.it_value = start;
  if (spec.it_value.tv_sec == 0 && spec.it_value.tv_nsec == 0) spec.it_value.tv_nsec = 1;
  if (timerfd_settime(timer_fd_, TFD_TIMER_ABSTIME, &spec, nullptr) != 0)
    return system_error("timerfd_settime");

  std::array<pollfd, 3> fds{{{timer_fd_, POLLIN, 0}, {event_fd_, POLLIN, 0}, {signal_fd_, POLLIN, 0}}};
  for (;;) {
    const int ready = ::poll(fds.data(), fds.size(), -1);
    if (ready < 0) {
      if (errno == EINTR) continue;
      return system_error("poll");
    }
    if ((fds[2].revents & POLLIN) != 0) {
      signalfd_siginfo info{};
      if (::read(signal_fd_, &info, sizeof info) == sizeof info) {
        last_signal_ = static_cast<int>(info.ssi_signo);
        return StopReason::kSignal;
      }
    }
    if ((fds[1].revents & POLLIN) != 0) {
      std::uint64_t count = 0;
      if (::read(event_fd_, &count, sizeof count) == sizeof count) {
        if (count >= kStopIncrement) return StopReason::kRequested;
        hub.command_step(clock.now());
      }
    }
    if ((fds[0].revents & POLLIN) != 0) {
      std::uint64_t expirations = 0;
      if (::read(timer_fd_, &expirations, sizeof expirations) == sizeof expirations && expirations > 0) {
        hub.count_overruns(expirations - 1);
        const Instant now = clock.now();
        hub.cycle(now);
        if (hooks.after_cycle) hooks.after_cycle(now);
      }
    }
  }
}

}  // namespace hubrt::runtime
