// The ladder-frame gripper's two confirm lines (both active = closed on the part), and the
// supervision that turns a gripper that does not do what its valve says into a latched fault.
//
// The lines change when the gripper arrives, and not necessarily together: they may disagree, or
// lag the valve, for up to the confirm time (valve actuation plus debouncing) before that counts.
#pragma once

#include <optional>
#include <string_view>

#include "hubrt/base/time.h"
#include "hubrt/runtime/text_buffer.h"

namespace hubrt::rsp_ecu {

// Not thread-safe; never allocates.
class GripperMonitor {
 public:
  enum class Confirm : unsigned char {
    kNotConnected,  // both lines off: gripper open
    kConnected,     // both lines on: gripper closed
    kMoving,        // they disagree, for less than the confirm time so far
    kFailed,        // they disagree for longer
    kUnknown,       // a line cannot be read: nothing is confirmed, nothing claimed
  };

  explicit GripperMonitor(Duration confirm_time) noexcept : confirm_time_(confirm_time) {}

  // The lines as read at `now` (a and b: active; readable: the read worked).
  void observe(bool a_readable, bool a, bool b_readable, bool b, Time now) noexcept;
  // The valve drives the gripper closed (`grab`) or open from `now` on (call every cycle; only a
  // change counts).
  void valve(bool grab, Time now) noexcept;
  // Checks the confirms against the valve while `active` (the gripper's tool is on the changer and
  // there is pressure). The gripper gets the confirm time from whichever came last: the valve's
  // change, or supervision becoming active; lines that disagree get it from when they began to.
  // Latches a fault when it fails.
  void supervise(bool active, Time now) noexcept;
  // Forgets a latched fault (a reset command).
  void reset() noexcept { fault_.clear(); }

  [[nodiscard]] Confirm confirm() const noexcept { return confirm_; }
  // "not_connected", "connected", "moving" or "failed".
  [[nodiscard]] std::string_view confirm_name() const noexcept;
  [[nodiscard]] bool faulted() const noexcept { return !fault_.empty(); }
  // The latched fault, for error_list (empty when none).
  [[nodiscard]] std::string_view fault() const noexcept { return fault_.view(); }

 private:
  Duration confirm_time_;
  Confirm confirm_ = Confirm::kNotConnected;
  bool line_a_ = false;
  bool line_b_ = false;
  std::optional<Time> disagree_since_;
  std::optional<bool> grab_;
  Time grab_since_{};
  std::optional<Time> active_since_;
  runtime::TextBuffer<160> fault_;
};

}  // namespace hubrt::rsp_ecu
