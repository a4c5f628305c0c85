// Devices whose answers come from the fuzz input: a CAN bus that receives the frames it is given,
// and a Modbus client that answers the lift drive's exchanges in lockstep with the harness. They
// stand where the hub's real device would be, so the hub's own decoding of what a device says is
// what the fuzzer exercises. A backend hands them out, with GPIO from the fake backend.
#pragma once

#include <array>
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <memory>
#include <mutex>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
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

// One round of the lift drive worker: the answer to its read of the input registers and to its
// write of the holding registers.
struct ModbusRound {
  ErrorCode read = ErrorCode::kOk;
  std::array<std::uint16_t, 4> input_registers{};
  ErrorCode write = ErrorCode::kOk;
};

// Hands rounds to the worker thread one at a time. Thread-safe.
class ModbusScript {
 public:
  // Lockstep: the next read waits for offer(). Free-running (the default): every read fails at
  // once with kTimeout, as a drive that does not answer.
  void set_lockstep(bool lockstep);
  // Makes `round` the answer of the next read (replacing one not yet taken).
  void offer(const ModbusRound& round);
  // Ends lockstep: a waiting read returns kUnavailable, later ones fail at once. Call before
  // destroying the logic whose worker may be waiting.
  void close();

  // For the client (the worker thread).
  Status read(std::span<std::uint16_t> out);
  Status write();

 private:
  std::mutex mutex_;
  std::condition_variable offered_;
  bool lockstep_ = false;
  bool has_round_ = false;
  ModbusRound round_;
  ErrorCode pending_write_ = ErrorCode::kTimeout;
};

// GPIO from the fake backend of the board; the CAN bus and Modbus client from the scripts.
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
  Expected<std::unique_ptr<hal::ModbusClient>> open_modbus(const hal::ModbusConfig& config) override;

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
