// ModbusClient on a libmodbus context: request/response with the configured timeout, errno
// mapping, and connection management (rate-limited reconnect after loss).
#pragma once

#include <array>
#include <memory>
#include <string>

#include <modbus/modbus.h>
#include <spdlog/logger.h>

#include "hubrt/base/time.h"
#include "hubrt/hal/modbus_client.h"

namespace hubrt::hal::libmodbus {

struct ContextDeleter {
  void operator()(modbus_t* ctx) const noexcept;  // closes, then frees
};
using ContextPtr = std::unique_ptr<modbus_t, ContextDeleter>;

class LibmodbusClient final : public ModbusClient {
 public:
  // `description` names the device and endpoint for logs, e.g. "lift_drive (Modbus TCP 10.0.0.5:502, unit
  // 1)". `connected`: whether the factory's first connect succeeded; if not, the first retry is due one
  // reconnect interval after `clock`'s now. `tcp`: a late TCP answer is avoided by starting a fresh
  // connection after a timeout or a mismatched answer; a serial line can only be flushed.
  LibmodbusClient(ContextPtr ctx, std::string description, bool tcp, Duration reconnect_interval,
                  const Clock& clock, bool connected);

 private:
  Status do_read_registers(RegisterKind kind, std::uint16_t address,
                           std::span<std::uint16_t> out) noexcept override;
  Status do_write_registers(std::uint16_t address, std::span<const std::uint16_t> values) noexcept override;
  Status do_read_bits(BitKind kind, std::uint16_t address, std::span<bool> out) noexcept override;
  Status do_write_coil(std::uint16_t address, bool value) noexcept override;

  // kOk when a request may go out now; kUnavailable while disconnected and no retry is due.
  Status ready() noexcept;
  // Maps errno after a failed call, drops the connection when it is gone, logs transitions.
  Status failed(int err, const char* operation, std::uint16_t address, std::size_t count) noexcept;
  void succeeded() noexcept;
  // Closes the connection; the next attempt is due at `retry_at`. `lost`: the link broke (the
  // next successful connect is logged); otherwise it is a deliberate resync after a timeout.
  void disconnect(Time retry_at, bool lost) noexcept;

  ContextPtr ctx_;
  const std::string description_;
  const bool tcp_;
  const Duration reconnect_interval_;
  const Clock& clock_;
  bool connected_;
  Time next_attempt_;
  bool flush_pending_ = false;
  bool log_next_connect_;      // after a loss, not after every resync
  int last_logged_errno_ = 0;  // log a failure once, until a success or a different failure
  // Taken from the opening thread: the client is often called from a worker thread (the lift's),
  // which must not be the first to touch spdlog's registry.
  std::shared_ptr<spdlog::logger> log_;
  std::array<std::uint8_t, MODBUS_MAX_READ_BITS> bits_{};  // bit reads land here, no allocation
};

}  // namespace hubrt::hal::libmodbus
