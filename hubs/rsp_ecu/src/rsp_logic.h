// The tool-changer node ("tool_changer"): the RSP on the robot. Outputs: the lock valve
// (energised = changer open) and the ladder-frame gripper valve (energised = grab). Inputs: the
// tool-ID lines, the gripper's two confirm lines, the pressure switch; and, through the hub
// file's subscriptions, the Dock ECU's State.
//
// Commands are state-based: action "lock" / "unlock" is the wanted lock state, `gripper` the
// wanted gripper state ("grab", "release", "keep" or empty = leave it as it is).
//
// Safety:
//   - The lock opens only while unlock_permitted() holds this cycle (the tool on the changer is
//     reported home by a fresh Dock ECU State). An "unlock" it does not allow is rejected, and an
//     "unlock" in force stops being obeyed the cycle the permission goes: the lock closes.
//   - Latched faults: pressure failure (switch off, or unreadable) and a failed gripper. While one
//     is latched, and whenever no command is in force or "reset" is, the node holds its safe
//     state: lock closed, gripper as it is (releasing could drop a ladder frame). A reset command
//     clears the latches; a fault still present latches again at once.
#pragma once

#include <array>
#include <vector>

#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/hub_api/remote_state.h"
#include "hubrt/runtime/node.h"

#include "dock_reflect.h"  // the Dock ECU's messages (its library is not ours to link)
#include "dock_typed.h"
#include "gripper_monitor.h"
#include "lock_position.h"
#include "rsp_messages.h"
#include "rsp_settings.h"
#include "tool_id.h"

namespace hubrt::rsp_ecu {

using DockInput = hub_api::RemoteState<hub_msgs::DockStateView>;

// The node's devices, opened by the hub type (open_rsp_devices() in rsp_ecu_hub_type.h).
struct RspDevices {
  hal::SupervisedOutput lock_valve;
  hal::SupervisedOutput gripper_valve;
  std::vector<hal::SupervisedInput> tool_lines;  // in the order of settings.tool_lines
  std::vector<hal::SupervisedInput> confirms;    // [A, B]
  hal::SupervisedInput pressure;
};

// The lock valve must stay de-energised (= closed) at start and on faults.
// Errors: kInvalidArgument, naming `where` the valve is configured (e.g. "board rpi4-rsp-ecu.yaml").
Expected<void> check_lock_valve(const hal::DigitalOutputConfig& lock, std::string_view where);

class RspLogic {
 public:
  using Command = hub_msgs::RspCommandView;
  using State = hub_msgs::RspState;
  static constexpr std::string_view kType = "tool_changer";
  static constexpr std::array<std::string_view, 3> kActions{"lock", "unlock", "reset"};
  static constexpr std::array<std::string_view, 4> kGripperStates{"grab", "release", "keep", ""};

  // Takes the devices the hub type opened (the lock valve de-energised, the gripper valve at the
  // board's initial level); a device that is not open is reported and retried. `dock` must
  // outlive the logic. Errors: device counts that do not match the settings (kInvalidArgument); a
  // lock valve configured to be energised at start or on faults (kInvalidArgument: energised =
  // open; open_rsp_devices refuses such a board before it opens anything).
  static Expected<RspLogic> create(const RspSettings& settings, RspDevices devices, DockInput& dock,
                                   Time now);

  RspLogic(RspLogic&&) noexcept = default;
  RspLogic& operator=(RspLogic&&) noexcept = default;

  // Rejects an unknown gripper state, and an "unlock" the interlock did not allow when last
  // evaluated (the reason goes to error_list; the command in force stays, the lock closed).
  bool validate(const Command& command, runtime::Problem& problem) const noexcept;
  void read_inputs(Time now) noexcept;
  // kFault: a pressure or gripper failure is latched; kDevicesMissing: a valve or an input is not
  // open.
  runtime::NodeCondition condition() const noexcept;
  void update(const Command* in_force, Time now) noexcept;
  void reset() noexcept;
  void report(State& state, runtime::ErrorList& errors, Time now) noexcept;
  // Closes the lock; the gripper stays as it is.
  void enter_safe_state() noexcept;

  // --- What the cycle decided, for tests and the report -------------------------------------------
  [[nodiscard]] const ToolId& tool() const noexcept { return tool_; }
  [[nodiscard]] std::string_view tool_name() const noexcept;
  [[nodiscard]] bool unlock_allowed() const noexcept { return unlock_allowed_; }
  [[nodiscard]] std::string_view unlock_blocked() const noexcept { return unlock_blocked_.view(); }
  [[nodiscard]] bool lock_open_commanded() const noexcept { return lock_.open_commanded(); }
  [[nodiscard]] bool gripper_grab() const noexcept { return gripper_grab_; }
  [[nodiscard]] bool pressure_ok() const noexcept { return pressure_ok_; }
  [[nodiscard]] bool in_safe_state() const noexcept { return safe_state_; }
  [[nodiscard]] bool fault_latched() const noexcept { return pressure_fault_ || gripper_.faulted(); }

 private:
  struct Line {
    hal::SupervisedInput input;
    bool level = false;
    bool readable = false;
    ErrorCode failure = ErrorCode::kOk;  // of the last read, when it failed
  };
  // The devices handed to create().
  struct Devices {
    hal::SupervisedOutput lock_valve;
    hal::SupervisedOutput gripper_valve;
    std::vector<Line> tool_lines;  // in the order of settings.tool_lines
    std::vector<Line> confirms;    // [A, B]
    Line pressure;
  };

  RspLogic(const RspSettings& settings, DockInput& dock, Devices devices, Time now);
  static void read_line(Line& line, Time now) noexcept;
  void read_pressure(Time now) noexcept;
  void evaluate_permission(Time now) noexcept;
  void report_line(const Line& line, runtime::ErrorList& errors) const noexcept;
  static void report_output(const hal::SupervisedOutput& output, Status last_write,
                            runtime::ErrorList& errors) noexcept;

  std::vector<std::string> tool_names_;
  std::size_t gripper_tool_ = 0;
  DockInput* dock_;
  Devices devices_;
  std::vector<ToolLineReading> tool_readings_;
  LockPosition lock_;
  GripperMonitor gripper_;

  ToolId tool_;
  bool pressure_ok_ = false;
  bool pressure_fault_ = false;
  runtime::TextBuffer<160> pressure_fault_text_;
  bool unlock_allowed_ = false;
  runtime::Problem unlock_blocked_;
  bool gripper_grab_ = true;
  bool safe_state_ = true;
  bool unlock_refused_ = false;  // an "unlock" is in force but not allowed this cycle
  Status lock_write_ = Status::ok();
  Status gripper_write_ = Status::ok();
};

}  // namespace hubrt::rsp_ecu
