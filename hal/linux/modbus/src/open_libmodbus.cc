#include "hubrt/hal/libmodbus/open_libmodbus.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <string>
#include <variant>

#include <arpa/inet.h>
#include <fmt/format.h>
#include <modbus/modbus.h>
#include <spdlog/spdlog.h>

#include "libmodbus_client.h"

namespace hubrt::hal::libmodbus {
namespace {

constexpr Duration kMaxResponseTimeout = std::chrono::hours(1);
constexpr int kMaxRtuUnitId = 247;  // 0 is broadcast, 248..255 reserved on a serial line

std::string describe(const ModbusConfig& config) {
  if (const auto* tcp = std::get_if<ModbusTcpEndpoint>(&config.endpoint)) {
    return fmt::format("{} (Modbus TCP {}:{}, unit {})", config.device, tcp->host, tcp->port, config.unit_id);
  }
  const auto& rtu = std::get<ModbusRtuEndpoint>(config.endpoint);
  return fmt::format("{} (Modbus RTU {} {} {}{}{}, unit {})", config.device, rtu.device, rtu.baud,
                     rtu.data_bits, rtu.parity, rtu.stop_bits, config.unit_id);
}

Error invalid(const std::string& where, const std::string& what) {
  return make_error(ErrorCode::kInvalidArgument, where + ": " + what);
}

Expected<void> validate(const ModbusConfig& config, const std::string& where) {
  if (config.response_timeout <= Duration::zero() || config.response_timeout > kMaxResponseTimeout) {
    return invalid(where, "response timeout must be positive and at most 1 h");
  }
  if (config.reconnect_interval < Duration::zero())
    return invalid(where, "reconnect interval must not be negative");
  if (const auto* tcp = std::get_if<ModbusTcpEndpoint>(&config.endpoint)) {
    in_addr parsed{};
    if (::inet_pton(AF_INET, tcp->host.c_str(), &parsed) != 1) {
      return invalid(where, "host '" + tcp->host + "' is not an IPv4 address (names are not looked up)");
    }
    if (tcp->port == 0) return invalid(where, "port 0");
    return {};
  }
  const auto& rtu = std::get<ModbusRtuEndpoint>(config.endpoint);
  if (config.unit_id < 1 || config.unit_id > kMaxRtuUnitId)
    return invalid(where, "RTU unit id must be 1..247");
  if (rtu.device.empty()) return invalid(where, "no serial device named");
  if (rtu.baud == 0) return invalid(where, "baud rate 0");
  if (rtu.parity != 'N' && rtu.parity != 'E' && rtu.parity != 'O')
    return invalid(where, "parity must be N, E or O");
  if (rtu.data_bits < 5 || rtu.data_bits > 8) return invalid(where, "data bits must be 5..8");
  if (rtu.stop_bits != 1 && rtu.stop_bits != 2) return invalid(where, "stop bits must be 1 or 2");
  return {};
}

ContextPtr new_context(const ModbusConfig& config) {
  if (const auto* tcp = std::get_if<ModbusTcpEndpoint>(&config.endpoint)) {
    return ContextPtr(modbus_new_tcp(tcp->host.c_str(), tcp->port));
  }
  const auto& rtu = std::get<ModbusRtuEndpoint>(config.endpoint);
  return ContextPtr(modbus_new_rtu(rtu.device.c_str(), static_cast<int>(rtu.baud), rtu.parity, rtu.data_bits,
                                   rtu.stop_bits));
}

Expected<void> configure(modbus_t* ctx, const ModbusConfig& config, const std::string& where) {
  const auto timeout_us =
      std::chrono::duration_cast<std::chrono::microseconds>(config.response_timeout).count();
  const auto seconds = static_cast<std::uint32_t>(timeout_us / 1'000'000);
  // At least 1 µs: a sub-microsecond timeout would round to 0, which libmodbus rejects.
  const auto micros =
      static_cast<std::uint32_t>(std::max<std::int64_t>(timeout_us % 1'000'000, seconds == 0 ? 1 : 0));
  // Byte timeout 0: the whole answer must arrive within the response timeout, so that the
  // response timeout bounds the call (libmodbus otherwise restarts a timer per chunk).
  if (modbus_set_response_timeout(ctx, seconds, micros) != 0 || modbus_set_byte_timeout(ctx, 0, 0) != 0 ||
      modbus_set_slave(ctx, config.unit_id) != 0 ||
      modbus_set_error_recovery(ctx, MODBUS_ERROR_RECOVERY_NONE) != 0) {
    return make_error(ErrorCode::kInvalidArgument,
                      where + ": libmodbus refused the settings: " + modbus_strerror(errno));
  }
  return {};
}

Error serial_open_error(int err, const std::string& where, const std::string& device) {
  const std::string cause = std::string(modbus_strerror(err));
  switch (err) {
    case ENOENT:
      return make_error(ErrorCode::kNotFound, where + ": no serial device " + device + " (" + cause + ")");
    case EACCES:
    case EPERM:
      return make_error(ErrorCode::kPermissionDenied, where + ": may not open " + device + " (" + cause +
                                                          "; is the user in group dialout?)");
    case EBUSY:
      return make_error(ErrorCode::kBusy, where + ": " + device + " is in use (" + cause + ")");
    case ENOTTY:
    case EINVAL:
      return make_error(ErrorCode::kIo, where + ": " + device +
                                            " is not a serial port or refused the settings (" + cause + ")");
    default:
      return make_error(ErrorCode::kIo, where + ": cannot open " + device + " (" + cause + ")");
  }
}

const Clock& system_clock() noexcept {
  static const SystemClock clock;
  return clock;
}

}  // namespace

Expected<std::unique_ptr<ModbusClient>> open_libmodbus(const ModbusConfig& config) {
  return open_libmodbus(config, system_clock());
}

Expected<std::unique_ptr<ModbusClient>> open_libmodbus(const ModbusConfig& config, const Clock& clock) {
  const std::string where = describe(config);
  if (Expected<void> valid = validate(config, where); !valid) return std::move(valid).error();
  ContextPtr ctx = new_context(config);
  if (!ctx) {
    return make_error(ErrorCode::kInvalidArgument,
                      where + ": libmodbus refused the endpoint: " + modbus_strerror(errno));
  }
  if (Expected<void> configured = configure(ctx.get(), config, where); !configured) {
    return std::move(configured).error();
  }
  const bool connected = modbus_connect(ctx.get()) == 0;
  if (!connected) {
    const int err = errno;
    if (std::holds_alternative<ModbusRtuEndpoint>(config.endpoint)) {
      return serial_open_error(err, where, std::get<ModbusRtuEndpoint>(config.endpoint).device);
    }
    // TCP: the server may come later; the client reconnects (see the header).
    modbus_close(ctx.get());
    spdlog::warn("{}: not reachable yet ({}); will retry at most every {} ms", where, modbus_strerror(err),
                 std::chrono::duration_cast<std::chrono::milliseconds>(config.reconnect_interval).count());
  }
  return std::unique_ptr<ModbusClient>(std::make_unique<LibmodbusClient>(
      std::move(ctx), where, std::holds_alternative<ModbusTcpEndpoint>(config.endpoint),
      config.reconnect_interval, clock, connected));
}

}  // namespace hubrt::hal::libmodbus
