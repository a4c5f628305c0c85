// The lift drive's Modbus exchanges (docs/protocols/lift-drive-modbus.md), stepped by the node's
// cycle: deterministic, no thread, no clock. The blocking calls run in the HAL (AsyncModbus);
// the link submits one request at a time and takes its completion in a later cycle, so the
// cycle never waits for the drive.
//
// Each request: write control word, target, speed and watchdog in one request (all or nothing on
// the drive), then read the input registers — so each reading shows what the write before it did,
// and the next write is decided from it, as the drive's rules want. The write is part of a request
// only when the previous request read the drive: without the drive's state there is nothing sound
// to write (the enable edge depends on it). Between that reading and the write lies one node cycle
// (100 ms at 10 Hz) where the old blocking worker had microseconds. A fault in that time switches
// the power stage off, and the enable bit held at 1 is no edge, so nothing switches on; only a drive
// that powered up anew in that cycle (control word back to 0) and answered at once would take a
// held enable bit as an edge. The link knows the drive's enable rule: the power stage switches on only on
// a 0→1 edge of the enable bit with no fault present, so when a move is wanted and the drive is
// disabled although enable was already written, it writes enable 0 once to make the next write an
// edge. A reset is one write with the reset bit (enable 0), and the bit drops again in the next.
//
// "Stop" is the last word: after every reading the link leaves the drive's stop control word with
// the device as its write-on-close, which the HAL sends when the device is closed.
#pragma once

#include <cstdint>
#include <memory>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/async_modbus.h"

namespace hubrt::tool_ecu {

struct LiftIntent {
  enum class Mode : std::uint8_t {
    kStop,  // halt and hold; the power stage stays as it is (never switched on)
    kMove,  // switch the power stage on if needed and move to the target
  };
  Mode mode = Mode::kStop;
  std::uint16_t target_tenth_mm = 0;  // kMove
  std::uint16_t speed_mm_s = 50;
  // Each increment asks for one reset-fault pulse (rising edge of the reset bit, enable 0).
  std::uint32_t reset_requests = 0;
  friend bool operator==(const LiftIntent&, const LiftIntent&) = default;
};

struct LiftSnapshot {
  bool answered = false;  // a read succeeded at least once
  Time read_at{};         // the `now` at which the request of the last successful read was submitted
  std::uint16_t position_tenth_mm = 0;
  std::uint16_t status_word = 0;  // protocol::lift_drive::status bits
  std::uint16_t fault_code = 0;   // protocol::lift_drive::FaultCode
  std::int16_t speed_mm_s = 0;
  ErrorCode last_error = ErrorCode::kOk;  // of the last completed request (kOk: it all worked)
  std::uint32_t failures_in_a_row = 0;
  bool write_refused = false;         // the drive answered the last write with an exception
  std::uint16_t written_control = 0;  // control word of the last successful write
  std::uint64_t rounds = 0;           // requests completed (or timed out)
};

// Plain single-threaded value; the device it owns documents its own thread-safety.
class LiftDriveLink {
 public:
  // `device` must not be null.
  LiftDriveLink(std::unique_ptr<hal::AsyncModbus> device, Duration poll_interval, std::uint16_t watchdog_ms);

  // Takes the completion of the request in flight, if it came (or its deadline passed).
  void poll(Time now) noexcept;
  // Submits a request carrying `intent` when none is in flight and the intent changed or
  // poll_interval passed since the last one.
  void send(const LiftIntent& intent, Time now) noexcept;

  [[nodiscard]] const LiftSnapshot& snapshot() const noexcept { return snap_; }
  [[nodiscard]] bool in_flight() const noexcept { return in_flight_; }
  [[nodiscard]] std::string_view description() const noexcept { return device_->description(); }

 private:
  void take(const hal::ModbusCompletion& done) noexcept;
  [[nodiscard]] std::uint16_t control_word(const LiftIntent& intent) noexcept;
  [[nodiscard]] std::uint16_t stop_control_word() const noexcept;

  std::unique_ptr<hal::AsyncModbus> device_;
  Duration poll_interval_;
  std::uint16_t watchdog_ms_;

  LiftSnapshot snap_;
  bool in_flight_ = false;
  bool sent_once_ = false;
  Time sent_at_{};
  LiftIntent sent_intent_;
  std::uint16_t sent_control_ = 0;  // of the request in flight, when it writes
  bool sent_write_ = false;
  bool last_read_ok_ = false;  // the last completed request read the drive: its state is current
  bool wrote_once_ = false;
  std::uint32_t resets_done_ = 0;
  std::uint16_t close_control_ = 0;   // the write-on-close left with the device (0: none yet)
  hal::ModbusCompletion completion_;  // storage for poll(), reused
};

}  // namespace hubrt::tool_ecu
