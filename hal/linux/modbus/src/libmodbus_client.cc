#include "libmodbus_client.h"

#include <cerrno>
#include <string_view>

#include <spdlog/spdlog.h>

#include "modbus_errors.h"

namespace hubrt::hal::libmodbus {
namespace {

// Requests beyond what one Modbus PDU carries, or past the end of the address space, are the
// caller's mistake: refuse them before they reach the wire.
Status check_range(std::uint16_t address, std::size_t count, std::size_t max_count) noexcept {
  if (count == 0 || count > max_count) return Status(ErrorCode::kInvalidArgument);
  if (address + count > 0x10000U) return Status(ErrorCode::kInvalidArgument);
  return Status::ok();
}

}  // namespace

void ContextDeleter::operator()(modbus_t* ctx) const noexcept {
  modbus_close(ctx);
  modbus_free(ctx);
}

LibmodbusClient::LibmodbusClient(ContextPtr ctx, std::string description, bool tcp,
                                 Duration reconnect_interval, const Clock& clock, bool connected)
    : ctx_(std::move(ctx)),
      description_(std::move(description)),
      tcp_(tcp),
      reconnect_interval_(reconnect_interval),
      clock_(clock),
      connected_(connected),
      next_attempt_(clock.now().mono + reconnect_interval),
      log_next_connect_(!connected),
      log_(spdlog::default_logger()) {}

Status LibmodbusClient::do_read_registers(RegisterKind kind, std::uint16_t address,
                                          std::span<std::uint16_t> out) noexcept {
  if (const Status s = check_range(address, out.size(), MODBUS_MAX_READ_REGISTERS); !s.is_ok()) return s;
  if (const Status s = ready(); !s.is_ok()) return s;
  const int n = static_cast<int>(out.size());
  const int rc = kind == RegisterKind::kHolding
                     ? modbus_read_registers(ctx_.get(), address, n, out.data())
                     : modbus_read_input_registers(ctx_.get(), address, n, out.data());
  if (rc != n) {
    return failed(rc < 0 ? errno : EMBBADDATA,
                  kind == RegisterKind::kHolding ? "read holding registers" : "read input registers", address,
                  out.size());
  }
  succeeded();
  return Status::ok();
}

Status LibmodbusClient::do_write_registers(std::uint16_t address,
                                           std::span<const std::uint16_t> values) noexcept {
  if (const Status s = check_range(address, values.size(), MODBUS_MAX_WRITE_REGISTERS); !s.is_ok()) return s;
  if (const Status s = ready(); !s.is_ok()) return s;
  // One register goes out as "write single register" (0x06), which every drive supports.
  const int n = static_cast<int>(values.size());
  const int rc = n == 1 ? modbus_write_register(ctx_.get(), address, values[0])
                        : modbus_write_registers(ctx_.get(), address, n, values.data());
  if (rc != n) return failed(rc < 0 ? errno : EMBBADDATA, "write registers", address, values.size());
  succeeded();
  return Status::ok();
}

Status LibmodbusClient::do_read_bits(BitKind kind, std::uint16_t address, std::span<bool> out) noexcept {
  if (const Status s = check_range(address, out.size(), MODBUS_MAX_READ_BITS); !s.is_ok()) return s;
  if (const Status s = ready(); !s.is_ok()) return s;
  const int n = static_cast<int>(out.size());
  const int rc = kind == BitKind::kCoil ? modbus_read_bits(ctx_.get(), address, n, bits_.data())
                                        : modbus_read_input_bits(ctx_.get(), address, n, bits_.data());
  if (rc != n) {
    return failed(rc < 0 ? errno : EMBBADDATA, kind == BitKind::kCoil ? "read coils" : "read discrete inputs",
                  address, out.size());
  }
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = bits_[i] != 0;
  succeeded();
  return Status::ok();
}

Status LibmodbusClient::do_write_coil(std::uint16_t address, bool value) noexcept {
  if (const Status s = ready(); !s.is_ok()) return s;
  const int rc = modbus_write_bit(ctx_.get(), address, value ? 1 : 0);
  if (rc != 1) return failed(rc < 0 ? errno : EMBBADDATA, "write coil", address, 1);
  succeeded();
  return Status::ok();
}

Status LibmodbusClient::ready() noexcept {
  if (connected_) {
    if (flush_pending_) {
      // A late answer to a timed-out request would otherwise be taken for the next one.
      modbus_flush(ctx_.get());
      flush_pending_ = false;
    }
    return Status::ok();
  }
  const Time now = clock_.now().mono;
  if (now < next_attempt_) return Status(ErrorCode::kUnavailable);
  // One attempt, bounded by the response timeout (libmodbus waits that long for the connect).
  if (modbus_connect(ctx_.get()) == 0) {
    connected_ = true;
    flush_pending_ = false;
    if (log_next_connect_) log_->info("{}: connected", description_);
    log_next_connect_ = false;
    return Status::ok();
  }
  const int err = errno;
  disconnect(now + reconnect_interval_, true);
  if (err != last_logged_errno_) {
    log_->warn("{}: cannot connect: {}; retrying at most every {} ms", description_, modbus_strerror(err),
               std::chrono::duration_cast<std::chrono::milliseconds>(reconnect_interval_).count());
    last_logged_errno_ = err;
  }
  return Status(ErrorCode::kUnavailable);
}

Status LibmodbusClient::failed(int err, const char* operation, std::uint16_t address,
                               std::size_t count) noexcept {
  const ModbusFailure failure = classify_modbus_errno(err);
  const Time now = clock_.now().mono;
  if (failure.connection_lost) {
    disconnect(now + reconnect_interval_, true);
  } else if (failure.flush_before_next && tcp_) {
    // A late answer would arrive after any flush and be read as the answer to the next request
    // (libmodbus drops the call on the transaction-id mismatch, and the offset persists): a fresh
    // connection, opened at once by the next call, cannot hold stale answers.
    disconnect(now, false);
  } else {
    flush_pending_ = failure.flush_before_next;
  }
  if (err != last_logged_errno_) {
    const std::string_view exception = modbus_exception_name(err);
    log_->warn("{}: {} at address {} (count {}) failed: {}{}", description_, operation, address, count,
               exception.empty() ? std::string_view(modbus_strerror(err)) : exception,
               failure.connection_lost ? "; connection dropped, will reconnect" : "");
    last_logged_errno_ = err;
  }
  return Status(failure.code);
}

void LibmodbusClient::succeeded() noexcept {
  if (last_logged_errno_ != 0) {
    log_->info("{}: requests succeed again", description_);
    last_logged_errno_ = 0;
  }
}

void LibmodbusClient::disconnect(Time retry_at, bool lost) noexcept {
  modbus_close(ctx_.get());
  log_next_connect_ = log_next_connect_ || lost;
  connected_ = false;
  flush_pending_ = false;
  next_attempt_ = retry_at;
}

}  // namespace hubrt::hal::libmodbus
