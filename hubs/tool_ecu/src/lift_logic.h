// The lift node: the smart tool's lifting system on a Modbus motor drive. It moves to named
// positions from the hub file ("home", "float" above the engine, "work"), reports position,
// target, motion and the drive's fault, and stops when anything is wrong.
//
// Safe state (no command in force, a latched fault, the drive not answering): stop — halt and
// hold; the power stage is never switched on for it. A drive fault and a drive that stopped
// answering latch until a reset; a reset also pulses the drive's reset-fault bit. Motion resumes
// only with a fresh "move" after the reset.
//
// A drive reading is valid for answer_within: an older one is never reported as current (the
// State's drive values read "unknown", `moving` false, drive_online false, reading_age_ms its
// age), and a drive that does not answer is not claimed "stopped": it cannot be told to stop, and
// runs on until its own communication watchdog stops it.
//
// Deterministic: no thread, no clock. The drive's Modbus exchanges go through the AsyncModbus
// device handed in (a request per cycle at most, its completion taken in a later cycle), and every
// time the logic judges is one the cycle passed in (lift_drive_link.h).
#pragma once

#include <array>
#include <memory>
#include <string_view>

#include <spdlog/logger.h>

#include "hubrt/hal/async_modbus.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/text_buffer.h"

#include "latched_fault.h"
#include "lift_drive_link.h"
#include "tool_messages.h"
#include "tool_settings.h"

namespace hubrt::tool_ecu {

class LiftLogic {
 public:
  using Command = hub_msgs::LiftCommandView;
  using State = hub_msgs::LiftState;
  static constexpr std::string_view kType = "lift";
  static constexpr std::array<std::string_view, 3> kActions{"move", "stop", "reset"};

  // Takes the drive's device (opened by the hub type from the board); `now`: the cycle's time at
  // creation. Closing the logic closes the device, whose write-on-close is the drive's "stop".
  // Errors: kInvalidArgument (no device).
  static Expected<LiftLogic> create(const LiftSettings& settings, std::unique_ptr<hal::AsyncModbus> drive,
                                    Time now, std::shared_ptr<spdlog::logger> log = nullptr);

  LiftLogic(LiftLogic&&) noexcept = default;
  LiftLogic& operator=(LiftLogic&&) noexcept = default;
  ~LiftLogic() = default;

  // move: position is one of the hub file's.
  bool validate(const Command& command, runtime::Problem& problem) const noexcept;
  void read_inputs(Time now) noexcept;
  // kFault: a drive fault or the drive having stopped answering is latched; kDevicesMissing: the
  // drive has not answered since start (requests keep going out).
  runtime::NodeCondition condition() const noexcept;
  void update(const Command* in_force, Time now) noexcept;
  void reset() noexcept;
  void report(State& state, runtime::ErrorList& errors, Time now) noexcept;
  // Asks for "stop" at once: a request goes out now unless one is still in flight (then with the
  // next cycle), stamped with the last time a cycle passed in.
  void enter_safe_state() noexcept;

  // For tests: what the drive said last.
  [[nodiscard]] const LiftSnapshot& snapshot() const noexcept { return link_.snapshot(); }

 private:
  LiftLogic(LiftSettings settings, std::unique_ptr<hal::AsyncModbus> drive, Time created,
            std::shared_ptr<spdlog::logger> log);
  [[nodiscard]] int position_index(std::string_view name) const noexcept;
  [[nodiscard]] int position_at() const noexcept;
  // The drive's values of this cycle's reading, or "unknown" for all of them when it is stale.
  void report_reading(State& state, bool current) const noexcept;
  void report_unknown_motion(runtime::ErrorList& errors) const noexcept;

  LiftSettings settings_;
  LiftDriveLink link_;
  std::string endpoint_;  // for messages, e.g. "lift_drive (tcp 127.0.0.1:1502, unit 1)"
  Time created_;
  Time last_now_;  // the latest time a cycle passed in, for enter_safe_state()
  std::shared_ptr<spdlog::logger> log_;

  LiftSnapshot snap_;  // this cycle's copy
  bool online_ = false;
  LatchedFault not_answering_;
  LatchedFault drive_fault_;
  LiftIntent intent_;
  int target_ = -1;  // index of the position a move in force goes to
};

// The name of a drive fault code ("overcurrent", ...), "" for none, "unknown" otherwise.
std::string_view fault_name(std::uint16_t code) noexcept;

}  // namespace hubrt::tool_ecu
