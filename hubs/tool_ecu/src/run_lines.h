// The smart tool's two run lines: run_forward is the run enable, run_reverse the direction
// (idle 0/0, forward 1/0, reverse 1/1). Lines that fail to open are opened again until they work.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/runtime/error_list.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::tool_ecu {

enum class RunOutput : std::uint8_t { kIdle, kForward, kReverse };
// "idle", "forward", "reverse".
std::string_view to_string(RunOutput output) noexcept;

// Not thread-safe: the cycle thread owns it. Driving an open line does not allocate; reopening does.
class RunLines {
 public:
  static constexpr Duration kReopenInterval = std::chrono::seconds(2);

  // Opens both lines now (they start at their board `initial` level); a line that fails is
  // reported and retried. Errors: a signal missing from the board (kNotFound, naming it).
  static Expected<RunLines> create(std::string_view run_forward, std::string_view run_reverse,
                                   const hal::BoardConfig& board, hal::Backend& backend, Time now);

  // Drives `output`. The direction never changes while the run enable is on: run_forward drops
  // first, so a change of direction cannot turn the spindle the wrong way for a moment.
  void drive(RunOutput output, Time now) noexcept;
  // Both lines to their board `safe` level (shutdown, fatal fault).
  void drive_safe() noexcept;
  // What the lines show, from the last levels written successfully.
  [[nodiscard]] RunOutput shown() const noexcept { return shown_; }
  // Both lines open.
  [[nodiscard]] bool all_open() const noexcept {
    return lines_[0].output != nullptr && lines_[1].output != nullptr;
  }
  // Lines not open or whose last write failed.
  void report(runtime::ErrorList& errors) const noexcept;

 private:
  struct Line {
    hal::DigitalOutputConfig config;
    std::unique_ptr<hal::DigitalOutput> output;
    runtime::TextBuffer<160> open_error;
    ErrorCode write_error = ErrorCode::kOk;
    bool level = false;  // last level written successfully
  };
  explicit RunLines(hal::Backend& backend) : backend_(&backend) {}
  void open(Line& line, Time now);
  bool write(Line& line, bool level, Time now) noexcept;
  void update_shown() noexcept;

  hal::Backend* backend_;
  std::array<Line, 2> lines_;  // run_forward, run_reverse
  Time next_open_{};
  RunOutput shown_ = RunOutput::kIdle;
};

}  // namespace hubrt::tool_ecu
