// Devices whose answers come from the fuzz input: a CAN bus that receives the frames it is given,
// and an asynchronous Modbus device that answers the lift drive's requests as the harness says.
// They stand where the hub's real device would be, so the hub's own decoding of what a device says
// is what the fuzzer exercises. A backend hands out the bus, with GPIO and Modbus clients from the
// fake backend; the script opens the Modbus device (the hub type would open it from the backend).
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <optional>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/async_modbus.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/can_bus.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/hal/modbus_client.h"

namespace hubrt::fuzz {

// What the bus receives next and how it reports itself. Single-threaded (the cycle's).
struct CanScript {
  std::deque<Result<hal::CanFrame>> incoming;  // receive() pops; empty: kTimeout
  hal::CanBusStatus status;
  ErrorCode send_result = ErrorCode::kOk;
};

// The answer to one request of the lift: to its write of the holding registers (when it writes)
// and to its read of the input registers.
struct ModbusRound {
  ErrorCode read = ErrorCode::kOk;
  std::array<std::uint16_t, 4> input_registers{};
  ErrorCode write = ErrorCode::kOk;
};

// Answers the requests of the device it opens, one at a time, as AsyncModbus's rules say (a write
// the drive did not answer is not followed by the read). Single-threaded: the cycle's; no thread
// anywhere, so a run is deterministic.
class ModbusScript {
 public:
  // Lockstep: the request in flight completes at the next poll after offer(). Free-running (the
  // default): every request completes at its first poll, unanswered (kTimeout), as a drive that
  // does not answer.
  void set_lockstep(bool lockstep);
  // Makes `round` the answer to the request in flight (replacing one not yet taken).
  void offer(const ModbusRound& round);
  // The device the logic gets; it uses this script, which must outlive it.
  std::unique_ptr<hal::AsyncModbus> open();
  // Requests completed so far.
  [[nodiscard]] std::uint64_t completed() const noexcept { return completed_; }

 private:
  friend class ScriptedAsyncModbus;
  // The completion of `batch` under the script, or nothing yet (lockstep, no round offered).
  std::optional<hal::ModbusCompletion> answer(const hal::ModbusBatch& batch);

  bool lockstep_ = false;
  std::optional<ModbusRound> round_;
  std::uint64_t completed_ = 0;
};

// GPIO and Modbus clients from the fake backend of the board; the CAN bus from the script.
// Thread-safety: as FakeBackend; the scripts as documented above.
class ScriptedBackend final : public hal::Backend {
 public:
  explicit ScriptedBackend(std::unique_ptr<hal::fake::FakeBackend> fake) : fake_(std::move(fake)) {}

  Expected<std::unique_ptr<hal::DigitalInput>> open_input(const hal::DigitalInputConfig& config) override {
    return fake_->open_input(config);
  }
  Expected<std::unique_ptr<hal::DigitalOutput>> open_output(const hal::DigitalOutputConfig& config) override {
    return fake_->open_output(config);
  }
  Expected<std::unique_ptr<hal::CanBus>> open_can(const hal::CanConfig& config) override;
  Expected<std::unique_ptr<hal::ModbusClient>> open_modbus(const hal::ModbusConfig& config) override {
    return fake_->open_modbus(config);
  }

  [[nodiscard]] CanScript& can() noexcept { return can_; }
  [[nodiscard]] ModbusScript& modbus() noexcept { return modbus_; }
  [[nodiscard]] hal::fake::FakeBackend& fake() noexcept { return *fake_; }

 private:
  std::unique_ptr<hal::fake::FakeBackend> fake_;
  CanScript can_;
  ModbusScript modbus_;
};

// The process's backend on the host-sim board, its simulators on `clock` (which must live as long
// as the process).
ScriptedBackend& scripted_backend(const Clock& clock);

}  // namespace hubrt::fuzz
