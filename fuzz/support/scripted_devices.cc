#include "scripted_devices.h"

#include "station_files.h"

namespace hubrt::fuzz {
namespace {

class ScriptedCanBus final : public hal::CanBus {
 public:
  explicit ScriptedCanBus(CanScript& script) : script_(script) {}

 private:
  Status do_send(const hal::CanFrame& frame, Duration /*timeout*/) noexcept override {
    if (frame.len > 8) return Status(ErrorCode::kInvalidArgument);
    return Status(script_.send_result);
  }
  Result<hal::CanFrame> do_receive(Duration /*timeout*/) noexcept override {
    if (script_.incoming.empty()) return Status(ErrorCode::kTimeout);
    Result<hal::CanFrame> next = script_.incoming.front();
    script_.incoming.pop_front();
    return next;
  }
  Status do_set_filters(std::span<const hal::CanFilter> /*filters*/) noexcept override {
    return Status::ok();
  }
  hal::CanBusStatus do_status() noexcept override { return script_.status; }

  CanScript& script_;
};

class ScriptedModbusClient final : public hal::ModbusClient {
 public:
  explicit ScriptedModbusClient(ModbusScript& script) : script_(script) {}

 private:
  Status do_read_registers(RegisterKind kind, std::uint16_t /*address*/,
                           std::span<std::uint16_t> out) noexcept override {
    if (kind != RegisterKind::kInput) return Status(ErrorCode::kProtocol);
    return script_.read(out);
  }
  Status do_write_registers(std::uint16_t /*address*/,
                            std::span<const std::uint16_t> /*values*/) noexcept override {
    return script_.write();
  }
  Status do_read_bits(BitKind /*kind*/, std::uint16_t /*address*/,
                      std::span<bool> /*out*/) noexcept override {
    return Status(ErrorCode::kProtocol);
  }
  Status do_write_coil(std::uint16_t /*address*/, bool /*value*/) noexcept override {
    return Status(ErrorCode::kProtocol);
  }

  ModbusScript& script_;
};

}  // namespace

void ModbusScript::set_lockstep(bool lockstep) {
  const std::lock_guard lock(mutex_);
  lockstep_ = lockstep;
  has_round_ = false;
}

void ModbusScript::offer(const ModbusRound& round) {
  {
    const std::lock_guard lock(mutex_);
    round_ = round;
    has_round_ = true;
  }
  offered_.notify_all();
}

void ModbusScript::close() {
  {
    const std::lock_guard lock(mutex_);
    lockstep_ = false;
    has_round_ = false;
  }
  offered_.notify_all();
}

Status ModbusScript::read(std::span<std::uint16_t> out) {
  std::unique_lock lock(mutex_);
  offered_.wait(lock, [&] { return !lockstep_ || has_round_; });
  if (!has_round_) {
    pending_write_ = ErrorCode::kTimeout;
    return Status(lockstep_ ? ErrorCode::kUnavailable : ErrorCode::kTimeout);
  }
  has_round_ = false;
  pending_write_ = round_.write;
  if (round_.read != ErrorCode::kOk) return Status(round_.read);
  for (std::size_t i = 0; i < out.size() && i < round_.input_registers.size(); ++i)
    out[i] = round_.input_registers[i];
  return Status::ok();
}

Status ModbusScript::write() {
  const std::lock_guard lock(mutex_);
  return Status(pending_write_);
}

Expected<std::unique_ptr<hal::CanBus>> ScriptedBackend::open_can(const hal::CanConfig& /*config*/) {
  return std::unique_ptr<hal::CanBus>(std::make_unique<ScriptedCanBus>(can_));
}

Expected<std::unique_ptr<hal::ModbusClient>> ScriptedBackend::open_modbus(
    const hal::ModbusConfig& /*config*/) {
  return std::unique_ptr<hal::ModbusClient>(std::make_unique<ScriptedModbusClient>(modbus_));
}

ScriptedBackend& scripted_backend(const Clock& clock) {
  static ScriptedBackend backend = [&] {
    auto fake = hal::fake::FakeBackend::create(host_sim_board(), clock);
    if (!fake) setup_failed(fake.error().message);
    return ScriptedBackend(std::move(*fake));
  }();
  return backend;
}

}  // namespace hubrt::fuzz
