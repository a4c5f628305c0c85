// Tells systemd how hubd is doing when it runs as a Type=notify service: READY once the hub
// runs, a watchdog ping every cycle that completes (no more often than half the watchdog time),
// STATUS lines, STOPPING on shutdown. Outside systemd every call does nothing.
#pragma once

#include <string_view>

#include "hubrt/base/time.h"

namespace hubrt::hubd {

// Thread-safety: call from the cycle thread only.
class SystemdNotifier {
 public:
  SystemdNotifier() noexcept;
  [[nodiscard]] bool under_systemd() const noexcept { return enabled_; }
  [[nodiscard]] Duration watchdog_interval() const noexcept { return watchdog_; }

  // systemd counts WatchdogSec= from the start of the process, and hubd pings only from its cycle:
  // a start-up slower than the watchdog (a loaded board, a DDS Security handshake, discovery) was
  // killed before it ran (seen in the deploy tier's VM with the unit's 2 s). So the start-up gets
  // its own allowance (sd_notify(3), WATCHDOG_USEC=) and ready() puts the unit's value back.
  // Outputs are safe meanwhile: no node is in control before the first cycle.
  void allow_startup(Duration allowance) const noexcept;
  // READY=1 with the status line, and the unit's own watchdog time back.
  void ready(std::string_view status) const noexcept;
  void status(std::string_view status) const noexcept;
  void stopping() const noexcept;
  // Pings the watchdog if half its period passed since the last ping. Allocation-free.
  void cycle_done(Time now) noexcept;

 private:
  bool enabled_ = false;
  Duration watchdog_{0};
  Time last_ping_{};
};

}  // namespace hubrt::hubd
