// The lift drive's Modbus exchanges (docs/protocols/lift-drive-modbus.md) on a thread of their
// own. A Modbus call blocks for up to its response timeout, so the cycle never makes one: it posts
// what it wants (a mailbox holding the latest intent) and reads the latest snapshot of the drive,
// stamped with the time it was read, so it can tell a drive that stopped answering.
//
// Each round: read the input registers; then write control word, target, speed and watchdog in
// one request (all or nothing on the drive). The worker knows the drive's enable rule: the power
// stage switches on only on a 0→1 edge of the enable bit with no fault present, so when a move is
// wanted and the drive is disabled although enable was already written, it writes enable 0 once
// to make the next write an edge.
#pragma once

#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <thread>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/modbus_client.h"

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
  Time read_at{};         // when the last successful read returned (the worker's clock)
  std::uint16_t position_tenth_mm = 0;
  std::uint16_t status_word = 0;  // protocol::lift_drive::status bits
  std::uint16_t fault_code = 0;   // protocol::lift_drive::FaultCode
  std::int16_t speed_mm_s = 0;
  ErrorCode last_error = ErrorCode::kOk;  // of the last round (kOk: it all worked)
  std::uint32_t failures_in_a_row = 0;
  bool write_refused = false;         // the drive answered the last write with an exception
  std::uint16_t written_control = 0;  // control word of the last successful write
  std::uint64_t rounds = 0;
};

// Thread-safety: post() and snapshot() may be called from any thread (the cycle); the client is
// used only by the worker thread. Both take a mutex for a copy, never during I/O.
class LiftDriveWorker {
 public:
  // Starts the thread. `clock` stamps the snapshots (the hub's clock) and must outlive the worker.
  LiftDriveWorker(std::unique_ptr<hal::ModbusClient> client, const Clock& clock, Duration poll_interval,
                  std::uint16_t watchdog_ms);
  // Stops the thread after the round in progress and one last write of "stop" (bounded by the
  // client's response timeout).
  ~LiftDriveWorker();
  LiftDriveWorker(const LiftDriveWorker&) = delete;
  LiftDriveWorker& operator=(const LiftDriveWorker&) = delete;

  // The latest intent wins; a changed one wakes the worker at once.
  void post(const LiftIntent& intent) noexcept;
  [[nodiscard]] LiftSnapshot snapshot() const noexcept;

 private:
  void run() noexcept;
  void round(const LiftIntent& intent) noexcept;
  void write_stop() noexcept;
  [[nodiscard]] std::uint16_t control_word(const LiftIntent& intent) noexcept;

  std::unique_ptr<hal::ModbusClient> client_;
  const Clock& clock_;
  const Duration poll_interval_;
  const std::uint16_t watchdog_ms_;

  mutable std::mutex mutex_;
  std::condition_variable wake_;
  LiftIntent intent_;      // guarded by mutex_
  LiftSnapshot shared_;    // guarded by mutex_
  bool stopping_ = false;  // guarded by mutex_

  // Worker thread only.
  LiftSnapshot local_;
  std::uint32_t resets_done_ = 0;
  bool wrote_once_ = false;

  std::thread thread_;  // last: starts after everything above is initialised
};

}  // namespace hubrt::tool_ecu
