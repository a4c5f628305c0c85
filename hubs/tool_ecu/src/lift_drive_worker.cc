#include "lift_drive_worker.h"

#include <array>

#include "hubrt/protocol/lift_drive_modbus.h"

namespace hubrt::tool_ecu {

namespace ld = protocol::lift_drive;

LiftDriveWorker::LiftDriveWorker(std::unique_ptr<hal::ModbusClient> client, const Clock& clock,
                                 Duration poll_interval, std::uint16_t watchdog_ms)
    : client_(std::move(client)),
      clock_(clock),
      poll_interval_(poll_interval),
      watchdog_ms_(watchdog_ms),
      thread_([this] { run(); }) {}

LiftDriveWorker::~LiftDriveWorker() {
  {
    const std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

void LiftDriveWorker::post(const LiftIntent& intent) noexcept {
  bool changed = false;
  {
    const std::lock_guard lock(mutex_);
    changed = !(intent == intent_);
    intent_ = intent;
  }
  if (changed) wake_.notify_one();
}

LiftSnapshot LiftDriveWorker::snapshot() const noexcept {
  const std::lock_guard lock(mutex_);
  return shared_;
}

void LiftDriveWorker::run() noexcept {
  std::unique_lock lock(mutex_);
  while (!stopping_) {
    const LiftIntent intent = intent_;
    lock.unlock();
    round(intent);
    lock.lock();
    shared_ = local_;
    // Wakes early for a new intent or for stopping; the predicate keeps a spurious wake-up from
    // starting a round early.
    const LiftIntent seen = intent;
    wake_.wait_for(lock, poll_interval_, [&] { return stopping_ || !(intent_ == seen); });
  }
  lock.unlock();
  write_stop();
}

void LiftDriveWorker::round(const LiftIntent& intent) noexcept {
  ++local_.rounds;
  std::array<std::uint16_t, ld::input::kCount> inputs{};
  const Status read = client_->read_input_registers(0, inputs);
  if (!read.is_ok()) {
    // Without the drive's state there is nothing sound to write (the enable edge depends on it).
    local_.last_error = read.code();
    ++local_.failures_in_a_row;
    return;
  }
  local_.answered = true;
  local_.read_at = clock_.now().mono;
  local_.position_tenth_mm = inputs[ld::input::kActualPosition];
  local_.status_word = inputs[ld::input::kStatusWord];
  local_.fault_code = inputs[ld::input::kFaultCode];
  local_.speed_mm_s = static_cast<std::int16_t>(inputs[ld::input::kActualSpeed]);

  const std::uint16_t control = control_word(intent);
  const std::uint16_t target =
      intent.mode == LiftIntent::Mode::kMove ? intent.target_tenth_mm : local_.position_tenth_mm;
  const std::array<std::uint16_t, ld::holding::kCount> holding{control, target, intent.speed_mm_s,
                                                               watchdog_ms_};
  const Status written = client_->write_registers(ld::holding::kControlWord, holding);
  local_.write_refused = written.code() == ErrorCode::kProtocol;
  local_.last_error = written.code();
  if (written.is_ok()) {
    local_.written_control = control;
    wrote_once_ = true;
    local_.failures_in_a_row = 0;
  } else if (!local_.write_refused) {
    ++local_.failures_in_a_row;
  }
}

std::uint16_t LiftDriveWorker::control_word(const LiftIntent& intent) noexcept {
  const bool enabled = (local_.status_word & ld::status::kEnabled) != 0;
  const bool fault = (local_.status_word & ld::status::kFault) != 0;
  const bool reset_was_written = wrote_once_ && (local_.written_control & ld::control::kResetFault) != 0;
  if (resets_done_ != intent.reset_requests) {
    // The pulse is one write with the reset bit (a rising edge, enable 0, as the drive's recovery
    // sequence wants); once it went out, the request is done and the bit drops again.
    if (!reset_was_written) return ld::control::kResetFault;
    resets_done_ = intent.reset_requests;
  }
  if (intent.mode == LiftIntent::Mode::kStop || fault) {
    return static_cast<std::uint16_t>(ld::control::kStop | (enabled ? ld::control::kEnable : 0));
  }
  const bool enable_was_written = wrote_once_ && (local_.written_control & ld::control::kEnable) != 0;
  if (!enabled && enable_was_written)
    return ld::control::kStop;  // enable 0 now, so the next write is an edge
  return ld::control::kEnable | ld::control::kMove;
}

void LiftDriveWorker::write_stop() noexcept {
  if (!local_.answered) return;
  const bool enabled = (local_.status_word & ld::status::kEnabled) != 0;
  const auto control = static_cast<std::uint16_t>(ld::control::kStop | (enabled ? ld::control::kEnable : 0));
  client_->write_register(ld::holding::kControlWord, control).ignore();  // best effort on the way out
}

}  // namespace hubrt::tool_ecu
