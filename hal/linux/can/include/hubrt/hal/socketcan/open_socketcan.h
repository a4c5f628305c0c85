// The Linux CAN backend: a CanBus on a SocketCAN raw socket (PF_CAN, SOCK_RAW, CAN_RAW).
#pragma once

#include <memory>

#include "hubrt/base/status.h"
#include "hubrt/hal/can_bus.h"

namespace hubrt::hal::socketcan {

// Opens a non-blocking raw CAN socket bound to `config.interface`, with `config.filters`
// (CAN_RAW_FILTER; none = receive everything), every error class enabled (CAN_RAW_ERR_FILTER:
// error frames update status() and are never returned as frames) and receive-overflow counting
// (SO_RXQ_OVFL → CanBusStatus::rx_dropped).
//
// Bus state: error frames (read by receive(), and from the head of the queue by status() and by a
// send() that finds the transmit queue full), the interface flags (down or removed → kDown; a
// re-created interface is re-bound, its filters set again), and for real controllers libsocketcan's state and
// error counters (at most every 250 ms; vcan has none, so there the error frames are the only source). While
// bus-off or down, send() and receive() return kUnavailable.
//
// An interface that exists but is down opens fine and reports kDown: systemd-networkd may bring
// it up later; calls then return kUnavailable until it is up. The bitrate is set by the OS; when
// libsocketcan can read it and it differs from config.bitrate, a warning is logged.
//
// Errors (the message names config.bus and the interface):
//   kInvalidArgument — empty or over-long interface name, invalid filter (id or mask wider than
//                      its frame format, more than 512), an interface that is not CAN;
//   kUnavailable     — the kernel has no SocketCAN (socket() fails with EAFNOSUPPORT: the can /
//                      can_raw modules are missing);
//   kNotFound        — no such network interface;
//   kPermissionDenied, kIo — anything else the socket calls report.
// Never blocks. The returned bus is not thread-safe (one owner).
Expected<std::unique_ptr<CanBus>> open_socketcan(const CanConfig& config);

}  // namespace hubrt::hal::socketcan
