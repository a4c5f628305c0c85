#include "systemd_notifier.h"

#include <cstdlib>
#include <string>

#include <systemd/sd-daemon.h>

namespace hubrt::hubd {

SystemdNotifier::SystemdNotifier() noexcept {
  const char* socket = std::getenv("NOTIFY_SOCKET");  // NOLINT(concurrency-mt-unsafe): start-up only
  enabled_ = socket != nullptr && *socket != '\0';
  std::uint64_t usec = 0;
  if (enabled_ && sd_watchdog_enabled(0, &usec) > 0) watchdog_ = std::chrono::microseconds(usec);
}

namespace {

std::string watchdog_usec(Duration watchdog) {
  return "WATCHDOG_USEC=" +
         std::to_string(std::chrono::duration_cast<std::chrono::microseconds>(watchdog).count());
}

}  // namespace

void SystemdNotifier::allow_startup(Duration allowance) const noexcept {
  if (watchdog_ <= Duration::zero() || allowance <= watchdog_) return;
  try {
    sd_notify(0, (watchdog_usec(allowance) + "\nWATCHDOG=1").c_str());
  } catch (...) {  // std::bad_alloc: start-up keeps the unit's watchdog time
  }
}

void SystemdNotifier::ready(std::string_view status) const noexcept {
  if (!enabled_) return;
  try {
    std::string message = "READY=1\n";
    if (watchdog_ > Duration::zero()) message += watchdog_usec(watchdog_) + "\nWATCHDOG=1\n";
    sd_notify(0, (message + "STATUS=" + std::string(status)).c_str());
  } catch (...) {  // std::bad_alloc: READY is then sent without the status
    sd_notify(0, "READY=1");
  }
}

void SystemdNotifier::status(std::string_view status) const noexcept {
  if (!enabled_) return;
  try {
    sd_notify(0, ("STATUS=" + std::string(status)).c_str());
  } catch (...) {  // a status line is not worth failing for
  }
}

void SystemdNotifier::stopping() const noexcept {
  if (enabled_) sd_notify(0, "STOPPING=1");
}

void SystemdNotifier::cycle_done(Time now) noexcept {
  if (watchdog_ <= Duration::zero() || now - last_ping_ < watchdog_ / 2) return;
  last_ping_ = now;
  sd_notify(0, "WATCHDOG=1");
}

}  // namespace hubrt::hubd
