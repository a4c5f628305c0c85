// Tells systemd how hubd is doing when it runs as a Type=notify service: READY once the hub
// runs, a watchdog ping every cycle that completes (no more often than half the watchdog time),
// STATUS lines, STOPPING on shutdown. Outside systemd every call does nothing.
//
// The notification protocol is written here rather than taken from libsystemd: sd_notify(3)
// (NOTES) documents it as one datagram with the "KEY=VALUE" lines, sent to the AF_UNIX socket
// named by $NOTIFY_SOCKET ('/' a path, '@' the abstract namespace), and sd_watchdog_enabled(3)
// the watchdog as $WATCHDOG_USEC (for the process in $WATCHDOG_PID when set). libsystemd was
// hubd's only use of the library, and it loaded eight more shared libraries (libgcrypt, liblz4,
// libzstd, liblzma, libcap...): about 0.8 MB of resident memory and their start-up time in every
// hubd. A $NOTIFY_SOCKET of another kind (vsock:) is not supported: hubd then runs as outside
// systemd.
#pragma once

#include <string_view>

#include <sys/socket.h>
#include <sys/un.h>

#include "hubrt/base/time.h"

namespace hubrt::hubd {

// Thread-safety: call from the cycle thread only.
class SystemdNotifier {
 public:
  // Reads $NOTIFY_SOCKET, $WATCHDOG_USEC and $WATCHDOG_PID. Start-up only: reads the environment.
  SystemdNotifier() noexcept;
  ~SystemdNotifier();
  SystemdNotifier(const SystemdNotifier&) = delete;
  SystemdNotifier& operator=(const SystemdNotifier&) = delete;
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
  // One datagram to $NOTIFY_SOCKET. Allocation-free.
  void send(std::string_view message) const noexcept;

  int socket_ = -1;
  sockaddr_un address_{};
  socklen_t address_length_ = 0;
  bool enabled_ = false;
  Duration watchdog_{0};
  Time last_ping_{};
};

}  // namespace hubrt::hubd
