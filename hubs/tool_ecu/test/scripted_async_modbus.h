// A test double of hal::AsyncModbus in front of the lift drive model (hal/fake LiftDrive, no
// server, no thread): a request completes only when the test says, against the drive at the time
// the test gives, so the lift logic runs entirely on the manual clock.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/async_modbus.h"
#include "hubrt/hal/fake/lift_drive.h"

namespace hubrt::tool_ecu::testing {

// The test's side of the double; outlives the device it opens. Single-threaded.
class DriveScript {
 public:
  // `request_timeout`: the device's deadline after submit() (the hub uses 3 response timeouts).
  explicit DriveScript(hal::fake::LiftDrive& drive, Duration request_timeout = std::chrono::milliseconds(300))
      : drive_(drive), request_timeout_(request_timeout) {}

  // The device the logic gets. At most one open at a time.
  std::unique_ptr<hal::AsyncModbus> open();

  // The request waiting, if any, runs now: against the drive at `at`, or — when `failure` is not
  // kOk — it fails with that code without reaching the drive (as a client's timeout). True if one ran.
  bool complete(Time at, ErrorCode failure = ErrorCode::kOk);

  [[nodiscard]] bool waiting() const noexcept { return waiting_.has_value(); }
  [[nodiscard]] const std::vector<hal::ModbusBatch>& submitted() const noexcept { return submitted_; }
  [[nodiscard]] std::uint64_t completed() const noexcept { return completed_; }
  [[nodiscard]] bool closed() const noexcept { return closed_; }
  // The write-on-close as the device holds it now (empty: none).
  [[nodiscard]] const std::vector<std::uint16_t>& write_on_close() const noexcept { return close_values_; }
  // When the device closes, its write-on-close goes to the drive at this time.
  void set_close_time(Time at) noexcept { close_time_ = at; }

 private:
  friend class ScriptedAsyncModbus;
  struct Waiting {
    std::uint64_t id = 0;
    hal::ModbusBatch batch;
  };

  hal::fake::LiftDrive& drive_;
  const Duration request_timeout_;
  std::vector<hal::ModbusBatch> submitted_;
  std::optional<Waiting> waiting_;
  std::optional<hal::ModbusCompletion> done_;  // the last request that ran (id, read, write, registers)
  std::uint64_t completed_ = 0;
  std::uint64_t last_id_ = 0;
  std::uint64_t latest_ = 0;
  Time latest_at_{};
  bool reported_ = true;
  std::uint16_t close_address_ = 0;
  std::vector<std::uint16_t> close_values_;
  Time close_time_{};
  bool closed_ = false;
};

}  // namespace hubrt::tool_ecu::testing
