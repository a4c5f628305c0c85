#include "lift_drive_link.h"

#include <array>

#include "hubrt/protocol/lift_drive_modbus.h"

namespace hubrt::tool_ecu {

namespace ld = protocol::lift_drive;

LiftDriveLink::LiftDriveLink(std::unique_ptr<hal::AsyncModbus> device, Duration poll_interval,
                             std::uint16_t watchdog_ms)
    : device_(std::move(device)), poll_interval_(poll_interval), watchdog_ms_(watchdog_ms) {}

void LiftDriveLink::poll(Time now) noexcept {
  if (!in_flight_ || !device_->poll(now, completion_)) return;
  in_flight_ = false;
  take(completion_);
}

void LiftDriveLink::take(const hal::ModbusCompletion& done) noexcept {
  ++snap_.rounds;
  if (sent_write_) {
    snap_.write_refused = done.write.code() == ErrorCode::kProtocol;
    if (done.write.is_ok()) {
      snap_.written_control = sent_control_;
      wrote_once_ = true;
    }
  }
  const bool write_unanswered = sent_write_ && !done.write.is_ok() && !snap_.write_refused;
  if (!done.read.is_ok() || done.register_count < ld::input::kCount) {
    // The request's own failure: the write's when the drive did not answer it (the read was not sent).
    snap_.last_error = write_unanswered    ? done.write.code()
                       : done.read.is_ok() ? ErrorCode::kProtocol
                                           : done.read.code();
    ++snap_.failures_in_a_row;
    last_read_ok_ = false;
    return;
  }
  last_read_ok_ = true;
  snap_.answered = true;
  // The drive was read after this; judging its age from here never makes it look younger.
  snap_.read_at = done.submitted_at;
  snap_.position_tenth_mm = done.registers[ld::input::kActualPosition];
  snap_.status_word = done.registers[ld::input::kStatusWord];
  snap_.fault_code = done.registers[ld::input::kFaultCode];
  snap_.speed_mm_s = static_cast<std::int16_t>(done.registers[ld::input::kActualSpeed]);
  snap_.last_error = sent_write_ ? done.write.code() : ErrorCode::kOk;
  if (!sent_write_ || done.write.is_ok()) {
    snap_.failures_in_a_row = 0;
  } else if (write_unanswered) {
    ++snap_.failures_in_a_row;
  }
  // The drive's "stop" for when the device closes, keeping the power stage as it now is.
  const std::uint16_t stop = stop_control_word();
  if (stop != close_control_ && device_->set_write_on_close(ld::holding::kControlWord, {&stop, 1}).is_ok()) {
    close_control_ = stop;
  }
}

void LiftDriveLink::send(const LiftIntent& intent, Time now) noexcept {
  if (in_flight_) return;
  if (sent_once_ && intent == sent_intent_ && now - sent_at_ < poll_interval_) return;
  hal::ModbusBatch batch;  // the write (decided from the last reading), then the read
  batch.read_bank = hal::ModbusRegisterBank::kInput;
  batch.read_address = 0;
  batch.read_count = ld::input::kCount;
  sent_write_ = last_read_ok_;
  if (sent_write_) {
    sent_control_ = control_word(intent);
    const std::uint16_t target =
        intent.mode == LiftIntent::Mode::kMove ? intent.target_tenth_mm : snap_.position_tenth_mm;
    batch.write_address = ld::holding::kControlWord;
    batch.write_count = ld::holding::kCount;
    batch.write_values[ld::holding::kControlWord] = sent_control_;
    batch.write_values[ld::holding::kTargetPosition] = target;
    batch.write_values[ld::holding::kSpeed] = intent.speed_mm_s;
    batch.write_values[ld::holding::kWatchdogMs] = watchdog_ms_;
  }
  const Result<std::uint64_t> submitted = device_->submit(batch, now);
  if (!submitted.is_ok()) {  // a malformed batch: a bug here, reported as this round's error
    snap_.last_error = submitted.status().code();
    return;
  }
  in_flight_ = true;
  sent_once_ = true;
  sent_at_ = now;
  sent_intent_ = intent;
}

std::uint16_t LiftDriveLink::control_word(const LiftIntent& intent) noexcept {
  const bool enabled = (snap_.status_word & ld::status::kEnabled) != 0;
  const bool fault = (snap_.status_word & ld::status::kFault) != 0;
  const bool reset_was_written = wrote_once_ && (snap_.written_control & ld::control::kResetFault) != 0;
  if (resets_done_ != intent.reset_requests) {
    // The pulse is one write with the reset bit (a rising edge, enable 0, as the drive's recovery
    // sequence wants); once it went out, the request is done and the bit drops again.
    if (!reset_was_written) return ld::control::kResetFault;
    resets_done_ = intent.reset_requests;
  }
  if (intent.mode == LiftIntent::Mode::kStop || fault) return stop_control_word();
  const bool enable_was_written = wrote_once_ && (snap_.written_control & ld::control::kEnable) != 0;
  if (!enabled && enable_was_written)
    return ld::control::kStop;  // enable 0 now, so the next write is an edge
  return ld::control::kEnable | ld::control::kMove;
}

std::uint16_t LiftDriveLink::stop_control_word() const noexcept {
  const bool enabled = (snap_.status_word & ld::status::kEnabled) != 0;
  return static_cast<std::uint16_t>(ld::control::kStop | (enabled ? ld::control::kEnable : 0));
}

}  // namespace hubrt::tool_ecu
