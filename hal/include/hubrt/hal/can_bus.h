// A CAN 2.0 bus (classic frames, up to 8 data bytes), as SocketCAN presents it.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::hal {

struct CanFrame {
  std::uint32_t id = 0;  // 11-bit, or 29-bit when extended
  bool extended = false;
  bool remote = false;
  std::uint8_t len = 0;  // 0..8
  std::array<std::uint8_t, 8> data{};
};

// A frame passes when (frame.id & mask) == (id & mask) and its extended flag matches.
struct CanFilter {
  std::uint32_t id = 0;
  std::uint32_t mask = 0;
  bool extended = false;
};

enum class CanBusState : std::uint8_t {
  kErrorActive,   // normal
  kErrorWarning,  // an error counter passed 96
  kErrorPassive,  // an error counter passed 127
  kBusOff,        // transmit error counter passed 255: the controller left the bus
  kDown,          // interface administratively down or gone
};

struct CanBusStatus {
  CanBusState state = CanBusState::kErrorActive;
  std::uint16_t tx_errors = 0;     // transmit error counter, when the backend knows it
  std::uint16_t rx_errors = 0;     // receive error counter, when the backend knows it
  std::uint32_t error_frames = 0;  // error frames seen since open
  std::uint32_t rx_dropped = 0;    // received frames dropped because the receive queue was full
};

struct CanConfig {
  std::string bus;                  // logical name used in error messages, e.g. "tool_bus"
  std::string interface;            // e.g. "can0", "vcan0"
  std::uint32_t bitrate = 500'000;  // documented here; the OS (systemd-networkd) sets it
  std::vector<CanFilter> filters;   // empty = receive everything
};

// Not thread-safe: one owner. Frames sent by this object are not received back by it.
class CanBus {
 public:
  virtual ~CanBus() = default;
  CanBus(const CanBus&) = delete;
  CanBus& operator=(const CanBus&) = delete;

  // Queues a frame for transmission, waiting at most `timeout` for room.
  // Errors: kInvalidArgument (len > 8), kTimeout (queue full), kUnavailable (down, bus-off), kIo.
  Status send(const CanFrame& frame, Duration timeout) noexcept { return do_send(frame, timeout); }
  // Returns the next frame that passes the filters, waiting at most `timeout` (0 = poll).
  // Errors: kTimeout (nothing arrived), kUnavailable (down, bus-off), kIo.
  Result<CanFrame> receive(Duration timeout) noexcept { return do_receive(timeout); }
  // Replaces the receive filters. Errors: kInvalidArgument, kIo.
  Status set_filters(std::span<const CanFilter> filters) noexcept { return do_set_filters(filters); }
  // Bus state and error counters as last observed. Never blocks.
  [[nodiscard]] CanBusStatus status() noexcept { return do_status(); }

 protected:
  CanBus() = default;

 private:
  virtual Status do_send(const CanFrame& frame, Duration timeout) noexcept = 0;
  virtual Result<CanFrame> do_receive(Duration timeout) noexcept = 0;
  virtual Status do_set_filters(std::span<const CanFilter> filters) noexcept = 0;
  virtual CanBusStatus do_status() noexcept = 0;
};

}  // namespace hubrt::hal
