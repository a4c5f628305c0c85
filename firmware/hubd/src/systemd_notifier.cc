#include "systemd_notifier.h"

#include <unistd.h>

#include <charconv>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <string>

namespace hubrt::hubd {
namespace {

std::string_view environment(const char* name) noexcept {
  // NOLINTNEXTLINE(concurrency-mt-unsafe): start-up only, before any thread exists.
  const char* value = std::getenv(name);
  return value != nullptr ? std::string_view(value) : std::string_view();
}

template <class Integer>
bool parse(std::string_view text, Integer& out) noexcept {
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), out);
  return ec == std::errc() && end == text.data() + text.size();
}

std::string watchdog_usec(Duration watchdog) {
  return "WATCHDOG_USEC=" +
         std::to_string(std::chrono::duration_cast<std::chrono::microseconds>(watchdog).count());
}

}  // namespace

SystemdNotifier::SystemdNotifier() noexcept {
  const std::string_view path = environment("NOTIFY_SOCKET");
  if (path.size() < 2 || (path[0] != '/' && path[0] != '@') || path.size() >= sizeof(address_.sun_path))
    return;
  address_.sun_family = AF_UNIX;
  std::memcpy(address_.sun_path, path.data(), path.size());
  if (path[0] == '@') address_.sun_path[0] = '\0';  // the abstract namespace: no terminating NUL
  address_length_ = static_cast<socklen_t>(offsetof(sockaddr_un, sun_path) + path.size());
  socket_ = ::socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  enabled_ = socket_ >= 0;
  if (!enabled_) return;
  // sd_watchdog_enabled(3): the watchdog is for this process unless $WATCHDOG_PID names another.
  std::uint64_t usec = 0;
  if (!parse(environment("WATCHDOG_USEC"), usec) || usec == 0) return;
  const std::string_view pid_text = environment("WATCHDOG_PID");
  pid_t pid = 0;
  if (!pid_text.empty() && (!parse(pid_text, pid) || pid != ::getpid())) return;
  watchdog_ = std::chrono::microseconds(usec);
}

SystemdNotifier::~SystemdNotifier() {
  if (socket_ >= 0) ::close(socket_);
}

void SystemdNotifier::send(std::string_view message) const noexcept {
  if (!enabled_) return;
  // A lost notification is not worth failing for: systemd then reports the unit as it sees it
  // (MSG_NOSIGNAL: never SIGPIPE).
  (void)::sendto(socket_, message.data(), message.size(), MSG_NOSIGNAL,
                 reinterpret_cast<const sockaddr*>(&address_), address_length_);
}

void SystemdNotifier::allow_startup(Duration allowance) const noexcept {
  if (watchdog_ <= Duration::zero() || allowance <= watchdog_) return;
  try {
    send(watchdog_usec(allowance) + "\nWATCHDOG=1");
  } catch (...) {  // std::bad_alloc: start-up keeps the unit's watchdog time
  }
}

void SystemdNotifier::ready(std::string_view status) const noexcept {
  if (!enabled_) return;
  try {
    std::string message = "READY=1\n";
    if (watchdog_ > Duration::zero()) message += watchdog_usec(watchdog_) + "\nWATCHDOG=1\n";
    send(message + "STATUS=" + std::string(status));
  } catch (...) {  // std::bad_alloc: READY is then sent without the status
    send("READY=1");
  }
}

void SystemdNotifier::status(std::string_view status) const noexcept {
  if (!enabled_) return;
  try {
    send("STATUS=" + std::string(status));
  } catch (...) {  // a status line is not worth failing for
  }
}

void SystemdNotifier::stopping() const noexcept {
  send("STOPPING=1");
}

void SystemdNotifier::cycle_done(Time now) noexcept {
  if (watchdog_ <= Duration::zero() || now - last_ping_ < watchdog_ / 2) return;
  last_ping_ = now;
  send("WATCHDOG=1");
}

}  // namespace hubrt::hubd
