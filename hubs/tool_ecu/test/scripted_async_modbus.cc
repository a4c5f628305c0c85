#include "scripted_async_modbus.h"

namespace hubrt::tool_ecu::testing {

// Follows AsyncModbus's rules (one waiting request, the latest replaces it, only the latest is
// reported, a deadline from the submit time) so the logic meets the same contract as in the hub.
class ScriptedAsyncModbus final : public hal::AsyncModbus {
 public:
  explicit ScriptedAsyncModbus(DriveScript& script) : script_(script) {}
  ~ScriptedAsyncModbus() override {
    script_.closed_ = true;
    script_.waiting_.reset();
    if (!script_.close_values_.empty()) {
      (void)script_.drive_.write_holding(script_.close_address_, script_.close_values_, script_.close_time_);
    }
  }
  ScriptedAsyncModbus(const ScriptedAsyncModbus&) = delete;
  ScriptedAsyncModbus& operator=(const ScriptedAsyncModbus&) = delete;

  Result<std::uint64_t> submit(const hal::ModbusBatch& batch, Time now) noexcept override {
    if (const Status valid = hal::check_batch(batch); !valid.is_ok()) return valid;
    const std::uint64_t id = ++script_.last_id_;
    script_.submitted_.push_back(batch);
    script_.waiting_ = DriveScript::Waiting{id, batch};
    script_.latest_ = id;
    script_.latest_at_ = now;
    script_.reported_ = false;
    return id;
  }

  bool poll(Time now, hal::ModbusCompletion& out) noexcept override {
    if (script_.reported_) return false;
    if (script_.done_ && script_.done_->id == script_.latest_) {
      out = *script_.done_;
    } else if (now - script_.latest_at_ > script_.request_timeout_) {
      if (script_.waiting_ && script_.waiting_->id == script_.latest_) script_.waiting_.reset();
      out = hal::ModbusCompletion{};
      out.read = Status(ErrorCode::kTimeout);
      out.write = Status(ErrorCode::kTimeout);
      out.timed_out = true;
    } else {
      return false;
    }
    out.id = script_.latest_;
    out.submitted_at = script_.latest_at_;
    out.completed_at = now;
    script_.reported_ = true;
    return true;
  }

  Status set_write_on_close(std::uint16_t address, std::span<const std::uint16_t> values) noexcept override {
    if (values.size() > hal::kMaxBatchRegisters) return Status(ErrorCode::kInvalidArgument);
    script_.close_address_ = address;
    script_.close_values_.assign(values.begin(), values.end());
    return Status::ok();
  }

  [[nodiscard]] std::string_view description() const noexcept override {
    return "lift_drive (scripted, unit 1)";
  }

 private:
  DriveScript& script_;
};

std::unique_ptr<hal::AsyncModbus> DriveScript::open() {
  closed_ = false;
  return std::make_unique<ScriptedAsyncModbus>(*this);
}

bool DriveScript::complete(Time at, ErrorCode failure) {
  if (!waiting_) return false;
  const Waiting job = *waiting_;
  waiting_.reset();
  ++completed_;
  hal::ModbusCompletion done;
  done.id = job.id;
  if (failure != ErrorCode::kOk) {  // the first call goes unanswered, the rest is not sent
    if (job.batch.write_count > 0) {
      done.write = Status(failure);
      if (job.batch.read_count > 0) done.read = Status(ErrorCode::kFailedPrecondition);
    } else {
      done.read = Status(failure);
    }
    done_ = done;
    return true;
  }
  if (job.batch.write_count > 0) {
    const auto refused = drive_.write_holding(
        job.batch.write_address,
        std::span<const std::uint16_t>(job.batch.write_values.data(), job.batch.write_count), at);
    done.write = Status(refused == hal::fake::ModbusException::kNone ? ErrorCode::kOk : ErrorCode::kProtocol);
  }
  if (job.batch.read_count > 0) {
    const hal::fake::LiftDriveRegisters registers = drive_.read(at);
    for (std::size_t i = 0; i < job.batch.read_count; ++i) {
      const std::size_t at_register = job.batch.read_address + i;
      done.registers[i] = at_register < registers.input.size() ? registers.input[at_register] : 0;
    }
    done.register_count = job.batch.read_count;
  }
  done_ = done;
  return true;
}

}  // namespace hubrt::tool_ecu::testing
