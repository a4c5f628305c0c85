// Modbus without blocking the caller: node logic submits a request (a batch: a write, then a
// read) and polls for its completion in a later cycle, passing the time in each call. A Modbus
// call blocks for up to its response timeout; the blocking calls run somewhere else (e.g. a worker
// thread in the HAL: threaded_async_modbus.h), so logic that uses this interface has no thread of
// its own and reads no clock — every time in a completion is one the caller passed in.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"

namespace hubrt::hal {

// Registers one batch reads or writes at most (a fixed size: nothing allocates per request).
inline constexpr std::size_t kMaxBatchRegisters = 16;

enum class ModbusRegisterBank : std::uint8_t {
  kInput,    // function 0x04
  kHolding,  // function 0x03
};

// One request: first the write of holding registers (when write_count > 0; function 0x10, all
// or nothing on a conforming unit), then the read (when read_count > 0), so the read shows what the
// write did. The read is not sent after a write the unit did not answer (any failure but kProtocol,
// an exception answer): a unit that just went silent is not asked again in the same request, so a
// request waits out at most one response timeout.
struct ModbusBatch {
  std::uint16_t write_address = 0;
  std::uint8_t write_count = 0;  // 0: no write
  std::array<std::uint16_t, kMaxBatchRegisters> write_values{};
  ModbusRegisterBank read_bank = ModbusRegisterBank::kInput;
  std::uint16_t read_address = 0;
  std::uint8_t read_count = 0;  // 0: no read
};

// How a request ended. Times are in the caller's time base: `submitted_at` is the `now` given to
// submit(), `completed_at` the `now` of the poll() that reported it. A value was read somewhere
// between the two; judging its age from `submitted_at` (as the lift does) never makes it look
// younger than it is.
struct ModbusCompletion {
  std::uint64_t id = 0;  // what submit() returned
  Time submitted_at{};
  Time completed_at{};
  // The write's outcome (kOk also when the batch had none); the ModbusClient's error codes. kProtocol
  // is an exception answer: the unit refused it.
  Status write;
  // The read's outcome (kOk also when the batch had none); kFailedPrecondition: not sent because the
  // write went unanswered.
  Status read;
  // No completion by submitted_at + the request timeout: read and write say kTimeout. The request
  // may still have reached the unit (a Modbus call cannot be withdrawn once sent).
  bool timed_out = false;
  std::array<std::uint16_t, kMaxBatchRegisters> registers{};  // the read's, read_count of them
  std::uint8_t register_count = 0;

  // The first failure (the write's, then the read's), or ok.
  [[nodiscard]] Status status() const noexcept { return write.is_ok() ? read : write; }
};

// Requests run one at a time, in the order submitted, with a queue of depth one: a request submitted
// while another runs waits; a later submit() replaces a request that is still waiting (it never runs
// and is never reported). poll() reports only the latest submission's completion, once: a request
// superseded by a later submit is not reported even if it ran.
//
// Time-outs: every blocking call is bounded by the client's response timeout; on top of that a
// request not complete by its deadline (the `now` given to submit() plus the device's request
// timeout, judged at the `now` given to poll()) is reported as timed out — and if it had not
// started yet it is withdrawn, so it never runs.
//
// Thread-safety: submit(), poll() and set_write_on_close() are called by one owner thread (the
// cycle's) and never block on the device (at most a short mutex for a copy). Destroying the device
// ends the request in progress (bounded by the response timeout per call), drops a waiting one,
// then sends the write-on-close (bounded likewise) — so destruction may block that long.
class AsyncModbus {
 public:
  virtual ~AsyncModbus() = default;
  AsyncModbus(const AsyncModbus&) = delete;
  AsyncModbus& operator=(const AsyncModbus&) = delete;

  // Queues `batch`; returns its id (counting from 1). Errors: kInvalidArgument (a count above
  // kMaxBatchRegisters, or neither a read nor a write).
  virtual Result<std::uint64_t> submit(const ModbusBatch& batch, Time now) noexcept = 0;
  // True, with `out` filled, when the latest submission completed (or its deadline passed) and was
  // not reported yet. False: nothing new (nothing submitted, or the request still runs).
  virtual bool poll(Time now, ModbusCompletion& out) noexcept = 0;
  // Holding registers to write once when the device is closed (destroyed), after the request in
  // progress — e.g. a drive's "stop", so it is the last word whatever the logic was doing. Replaces
  // the previous one; an empty span clears it. Errors: kInvalidArgument (above kMaxBatchRegisters).
  virtual Status set_write_on_close(std::uint16_t address,
                                    std::span<const std::uint16_t> values) noexcept = 0;

  // The device as messages name it, e.g. "lift_drive (tcp 127.0.0.1:1502, unit 1)".
  [[nodiscard]] virtual std::string_view description() const noexcept = 0;

 protected:
  AsyncModbus() = default;
};

// kInvalidArgument when `batch` has a count above kMaxBatchRegisters or does nothing; for
// implementations' submit().
[[nodiscard]] constexpr Status check_batch(const ModbusBatch& batch) noexcept {
  if (batch.read_count > kMaxBatchRegisters || batch.write_count > kMaxBatchRegisters) {
    return Status(ErrorCode::kInvalidArgument);
  }
  if (batch.read_count == 0 && batch.write_count == 0) return Status(ErrorCode::kInvalidArgument);
  return Status::ok();
}

}  // namespace hubrt::hal
