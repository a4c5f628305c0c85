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

}  // namespace

class ScriptedAsyncModbus final : public hal::AsyncModbus {
 public:
  explicit ScriptedAsyncModbus(ModbusScript& script) : script_(script) {}

  Result<std::uint64_t> submit(const hal::ModbusBatch& batch, Time now) noexcept override {
    if (const Status valid = hal::check_batch(batch); !valid.is_ok()) return valid;
    batch_ = batch;
    submitted_at_ = now;
    in_flight_ = true;
    return ++last_id_;
  }
  bool poll(Time now, hal::ModbusCompletion& out) noexcept override {
    if (!in_flight_) return false;
    std::optional<hal::ModbusCompletion> done = script_.answer(batch_);
    if (!done) return false;
    in_flight_ = false;
    out = *done;
    out.id = last_id_;
    out.submitted_at = submitted_at_;
    out.completed_at = now;
    return true;
  }
  Status set_write_on_close(std::uint16_t /*address*/,
                            std::span<const std::uint16_t> values) noexcept override {
    return values.size() > hal::kMaxBatchRegisters ? Status(ErrorCode::kInvalidArgument) : Status::ok();
  }
  [[nodiscard]] std::string_view description() const noexcept override { return "lift_drive (scripted)"; }

 private:
  ModbusScript& script_;
  hal::ModbusBatch batch_;
  Time submitted_at_{};
  bool in_flight_ = false;
  std::uint64_t last_id_ = 0;
};

void ModbusScript::set_lockstep(bool lockstep) {
  lockstep_ = lockstep;
  round_.reset();
}

void ModbusScript::offer(const ModbusRound& round) {
  round_ = round;
}

std::unique_ptr<hal::AsyncModbus> ModbusScript::open() {
  return std::make_unique<ScriptedAsyncModbus>(*this);
}

std::optional<hal::ModbusCompletion> ModbusScript::answer(const hal::ModbusBatch& batch) {
  if (lockstep_ && !round_) return std::nullopt;
  ModbusRound round;
  if (round_) {
    round = *round_;
  } else {  // free-running: nobody answers
    round.read = ErrorCode::kTimeout;
    round.write = ErrorCode::kTimeout;
  }
  round_.reset();
  ++completed_;
  hal::ModbusCompletion done;
  if (batch.write_count > 0) done.write = Status(round.write);
  if (batch.read_count > 0) {
    if (!done.write.is_ok() && done.write.code() != ErrorCode::kProtocol) {
      done.read = Status(ErrorCode::kFailedPrecondition);
    } else if (round.read != ErrorCode::kOk) {
      done.read = Status(round.read);
    } else {
      for (std::size_t i = 0; i < batch.read_count && i < round.input_registers.size(); ++i) {
        done.registers[i] = round.input_registers[i];
      }
      done.register_count = batch.read_count;
    }
  }
  return done;
}

Expected<std::unique_ptr<hal::CanBus>> ScriptedBackend::open_can(const hal::CanConfig& /*config*/) {
  return std::unique_ptr<hal::CanBus>(std::make_unique<ScriptedCanBus>(can_));
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
