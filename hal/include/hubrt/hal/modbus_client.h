// A Modbus master talking to one unit (slave) over RTU or TCP.
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <variant>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::hal {

struct ModbusTcpEndpoint {
  std::string host = "127.0.0.1";
  std::uint16_t port = 502;
};

struct ModbusRtuEndpoint {
  std::string device = "/dev/ttyUSB0";
  std::uint32_t baud = 19200;
  char parity = 'E';  // 'N', 'E' or 'O'
  int data_bits = 8;
  int stop_bits = 1;
};

struct ModbusConfig {
  std::string device;  // logical name used in error messages, e.g. "lift_drive"
  std::variant<ModbusTcpEndpoint, ModbusRtuEndpoint> endpoint;
  std::uint8_t unit_id = 1;
  Duration response_timeout = std::chrono::milliseconds(100);
  // After a lost connection, calls fail fast with kUnavailable until this much time has passed,
  // then the next call tries to reconnect.
  Duration reconnect_interval = std::chrono::milliseconds(500);
};

// Every call is bounded by the configured response timeout (plus, for TCP, one connect attempt).
// Not thread-safe: one owner.
// Errors common to all calls: kTimeout (no answer), kUnavailable (not connected / reconnect
// pending), kProtocol (exception response or malformed answer), kInvalidArgument (count 0 or
// beyond the protocol limit), kIo.
class ModbusClient {
 public:
  virtual ~ModbusClient() = default;
  ModbusClient(const ModbusClient&) = delete;
  ModbusClient& operator=(const ModbusClient&) = delete;

  Status read_holding_registers(std::uint16_t address, std::span<std::uint16_t> out) noexcept {
    return do_read_registers(RegisterKind::kHolding, address, out);
  }
  Status read_input_registers(std::uint16_t address, std::span<std::uint16_t> out) noexcept {
    return do_read_registers(RegisterKind::kInput, address, out);
  }
  Status write_register(std::uint16_t address, std::uint16_t value) noexcept {
    return do_write_registers(address, std::span<const std::uint16_t>(&value, 1));
  }
  Status write_registers(std::uint16_t address, std::span<const std::uint16_t> values) noexcept {
    return do_write_registers(address, values);
  }
  Status read_coils(std::uint16_t address, std::span<bool> out) noexcept {
    return do_read_bits(BitKind::kCoil, address, out);
  }
  Status read_discrete_inputs(std::uint16_t address, std::span<bool> out) noexcept {
    return do_read_bits(BitKind::kDiscreteInput, address, out);
  }
  Status write_coil(std::uint16_t address, bool value) noexcept { return do_write_coil(address, value); }

 protected:
  ModbusClient() = default;
  enum class RegisterKind : std::uint8_t { kHolding, kInput };
  enum class BitKind : std::uint8_t { kCoil, kDiscreteInput };

 private:
  virtual Status do_read_registers(RegisterKind kind, std::uint16_t address,
                                   std::span<std::uint16_t> out) noexcept = 0;
  virtual Status do_write_registers(std::uint16_t address,
                                    std::span<const std::uint16_t> values) noexcept = 0;
  virtual Status do_read_bits(BitKind kind, std::uint16_t address, std::span<bool> out) noexcept = 0;
  virtual Status do_write_coil(std::uint16_t address, bool value) noexcept = 0;
};

}  // namespace hubrt::hal
