// The smart tool's two run lines: run_forward is the run enable, run_reverse the direction
// (idle 0/0, forward 1/0, reverse 1/1), on two supervised outputs (opened again with back-off
// when their chip goes away: hubrt/hal/common/supervised_device.h).
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "hubrt/base/time.h"
#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/runtime/error_list.h"

namespace hubrt::tool_ecu {

enum class RunOutput : std::uint8_t { kIdle, kForward, kReverse };
// "idle", "forward", "reverse".
std::string_view to_string(RunOutput output) noexcept;

// Not thread-safe: the cycle thread owns it. Driving an open line does not allocate; reopening does.
class RunLines {
 public:
  // The lines as the hub type opened them (at their board `initial` level); one that is not open
  // is reported and opened again by drive().
  RunLines(hal::SupervisedOutput run_forward, hal::SupervisedOutput run_reverse) noexcept
      : lines_{Line{std::move(run_forward)}, Line{std::move(run_reverse)}} {}

  // Drives `output`. The direction never changes while the run enable is on: run_forward drops
  // first, so a change of direction cannot turn the spindle the wrong way for a moment. A line
  // opened again starts at its `initial` level, and the rule holds across that too.
  void drive(RunOutput output, Time now) noexcept;
  // Both open lines to their board `safe` level (shutdown, fatal fault).
  void drive_safe() noexcept;
  // What the lines show, from the levels they are driven to (a line not open drives nothing:
  // inactive).
  [[nodiscard]] RunOutput shown() const noexcept { return shown_; }
  // Both lines open.
  [[nodiscard]] bool all_open() const noexcept {
    return lines_[0].output.is_open() && lines_[1].output.is_open();
  }
  // Lines not open or whose last write failed.
  void report(runtime::ErrorList& errors) const noexcept;

 private:
  struct Line {
    hal::SupervisedOutput output;
    ErrorCode write_error = ErrorCode::kOk;
  };
  void write(Line& line, bool level, Time now) noexcept;
  void update_shown() noexcept;

  std::array<Line, 2> lines_;  // run_forward, run_reverse
  RunOutput shown_ = RunOutput::kIdle;
};

}  // namespace hubrt::tool_ecu
