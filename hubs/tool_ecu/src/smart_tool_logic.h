// The smart tool node: the nutrunner's controller on CAN, its two run lines, the handle's manual
// buttons, the torque-reached and summary-alarm inputs, the arm position sensors, and the robot's
// grip on the tool from the RSP ECU's State.
//
// Interlocks (DESIGN.md §2): the planner may run the tool only while the robot holds the smart
// tool (a fresh RSP ECU State says so; a lost one counts as "not allowed"), the torque is not
// reached (forward) and the arm is in operating position. The handle's buttons work only while
// the robot is known not to hold the tool. "inhibit", the summary alarm, a controller alarm, a
// lost controller and a CAN bus fault force idle; the faults latch until a reset.
//
// Tightenings have an identity: "tighten" with run_id R runs once. When it ends (result from the
// controller, or stopped by an interlock, or aborted by a fault) R is done and last_result
// reports it; repeating the command changes nothing, the next tightening is R' != R.
#pragma once

#include <array>
#include <memory>
#include <string_view>
#include <vector>

#include <spdlog/logger.h>

#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/runtime/node.h"

#include "arm_position.h"
#include "latched_fault.h"
#include "operator_presence.h"
#include "robot_holder.h"
#include "run_lines.h"
#include "tool_controller.h"
#include "tool_messages.h"
#include "tool_settings.h"

namespace hubrt::tool_ecu {

// The node's devices, opened by the hub type (open_smart_tool_devices() in tool_ecu_hub_type.h).
struct SmartToolDevices {
  hal::SupervisedOutput run_forward;
  hal::SupervisedOutput run_reverse;
  std::array<hal::SupervisedInput, 3> arm;  // home, pre-home, out-of-range
  hal::SupervisedInput button_forward;
  hal::SupervisedInput button_reverse;
  hal::SupervisedInput torque_reached;
  hal::SupervisedInput summary_alarm;
  hal::SupervisedCanBus bus;  // filtered for the controller (ToolController::bus_config)
};

class SmartToolLogic {
 public:
  using Command = hub_msgs::SmartToolCommandView;
  using State = hub_msgs::SmartToolState;
  static constexpr std::string_view kType = "smart_tool";
  static constexpr std::array<std::string_view, 5> kActions{"idle", "tighten", "loosen", "inhibit", "reset"};

  // Hub-side reasons a run ended NOK, beyond the controller's (protocol::smart_tool::nok_reason,
  // the low 8 bits).
  static constexpr std::uint16_t kControllerLost = 0x0100;  // no heartbeat during the run
  static constexpr std::uint16_t kBusFault = 0x0200;        // our CAN bus failed during the run
  static constexpr std::uint16_t kNotStarted = 0x0400;      // the controller did not confirm the Start
  static constexpr std::uint16_t kNoResult = 0x0800;        // the run ended without a result frame

  // Takes the run lines, inputs and the CAN bus the hub type opened; what is not open is reported
  // in the State and retried. `holder` tells whether the robot holds the tool. Never fails today;
  // Expected like every logic's create.
  static Expected<SmartToolLogic> create(const SmartToolSettings& settings, SmartToolDevices devices,
                                         std::unique_ptr<ToolHolderView> holder, Time now,
                                         std::shared_ptr<spdlog::logger> log = nullptr);

  // The collaborative interlock (settings' operator_state): from now on a planner's tighten or
  // reverse runs only while `presence` says an operator is verified. The manual buttons are the
  // operator's own hands on the tool and need no badge.
  void require_operator(std::unique_ptr<OperatorPresenceView> presence) noexcept {
    operator_ = std::move(presence);
  }

  SmartToolLogic(SmartToolLogic&&) noexcept = default;
  SmartToolLogic& operator=(SmartToolLogic&&) noexcept = default;
  ~SmartToolLogic() = default;

  // tighten: run_id 1.., program one of the hub file's.
  bool validate(const Command& command, runtime::Problem& problem) const noexcept;
  void read_inputs(Time now) noexcept;
  // kFault: a controller loss, bus fault, controller alarm or summary alarm is latched (a cause
  // still present after a reset is not latched: the logic keeps the tool idle for it itself, and
  // the reset must reach it to clear the controller's alarm); a program the controller rejected
  // only blocks that program. kDevicesMissing: the CAN bus, a run line or an input is not open.
  runtime::NodeCondition condition() const noexcept;
  void update(const Command* in_force, Time now) noexcept;
  void reset() noexcept;
  void report(State& state, runtime::ErrorList& errors, Time now) noexcept;
  void enter_safe_state() noexcept;

  // For tests.
  [[nodiscard]] RunOutput output() const noexcept { return lines_.shown(); }
  [[nodiscard]] ArmPosition arm_position() const noexcept { return arm_; }

 private:
  enum class Kind : std::uint8_t { kNone, kTighten, kLoosen, kManualForward, kManualReverse };
  enum class Phase : std::uint8_t { kIdle, kSelecting, kStarting, kRunning, kStopping };

  // What the command in force and the inputs ask for this cycle.
  struct Want {
    Kind kind = Kind::kNone;
    std::uint32_t run_id = 0;
    int program = -1;  // index into settings_.programs
  };
  struct Run {
    Phase phase = Phase::kIdle;
    Want what;
    std::uint8_t expected_counter = 0;  // the controller's run counter for this run
    std::uint64_t status_seen_at_send = 0;
    Time sent_at{};          // last frame sent for this run (select, start, stop)
    Time phase_since{};      // phase entered
    bool confirmed = false;  // the controller's status showed this run running
    bool ended = false;      // the status showed it ended; its result is awaited
    Time ended_at{};
  };
  struct LastResult {
    bool valid = false;
    bool from_controller = false;
    std::uint32_t run_id = 0;
    int program = -1;
    bool ok = false;
    std::uint16_t torque_cnm = 0;
    std::uint16_t angle_ddeg = 0;
    std::uint16_t reasons = 0;
    std::uint8_t run_counter = 0;
  };

  struct Inputs {
    hal::SupervisedInput button_forward;
    hal::SupervisedInput button_reverse;
    hal::SupervisedInput torque_reached;
    hal::SupervisedInput summary_alarm;
  };

  SmartToolLogic(SmartToolSettings settings, RunLines lines, ArmSensors arm, Inputs inputs,
                 ToolController controller, std::unique_ptr<ToolHolderView> holder,
                 std::shared_ptr<spdlog::logger> log);

  bool read_input(hal::SupervisedInput& input, bool& unreadable, Time now) noexcept;
  void observe_faults(Time now) noexcept;

  // Interlocks (smart_tool_interlocks.cc).
  Want decide(const Command* in_force, Time now) noexcept;
  // Each returns true when something forbids running now, and says what in blocked_by_.
  bool fault_blocks() noexcept;
  bool planner_blocked(bool forward, int program) noexcept;
  Want manual() noexcept;

  // The run through the controller (smart_tool_run_sequence.cc).
  void begin(const Want& want, Time now) noexcept;
  void send_start(Time now) noexcept;
  void stop(Time now) noexcept;
  void advance(Time now) noexcept;
  void finish(const protocol::smart_tool::RunResult* result, std::uint16_t hub_reasons) noexcept;
  void abort_for_fault() noexcept;
  void note_late_result(const protocol::smart_tool::RunResult& result) noexcept;
  [[nodiscard]] int selected_program() const noexcept;
  [[nodiscard]] bool is_forward(Kind kind) const noexcept {
    return kind == Kind::kTighten || kind == Kind::kManualForward;
  }
  [[nodiscard]] RunOutput wanted_output() const noexcept;
  [[nodiscard]] std::string_view activity() const noexcept;

  // The State (smart_tool_report.cc).
  // The controller's status values, or "unknown" for all of them when the status is stale.
  void report_status(State& state, Time now) noexcept;

  SmartToolSettings settings_;
  RunLines lines_;
  ArmSensors arm_sensors_;
  ToolController controller_;
  std::unique_ptr<ToolHolderView> holder_;
  std::unique_ptr<OperatorPresenceView> operator_;  // null: no operator interlock
  std::shared_ptr<spdlog::logger> log_;
  Inputs inputs_;

  // Inputs of this cycle.
  ArmPosition arm_ = ArmPosition::kUnknown;
  HolderReading holder_reading_;
  OperatorReading operator_reading_;
  bool pressed_forward_ = false;
  bool pressed_reverse_ = false;
  bool torque_input_ = false;
  bool alarm_input_ = false;
  bool torque_unreadable_ = false;          // an unreadable torque-reached input forbids forward runs
  bool alarm_unreadable_ = false;           // an unreadable summary-alarm input forbids running at all
  bool inputs_known_ = false;               // buttons, torque-reached and summary alarm all read
  ErrorCode input_error_ = ErrorCode::kOk;  // of the last failed button / torque / alarm read
  std::string_view input_error_signal_;

  LatchedFault controller_lost_;
  LatchedFault bus_fault_;
  LatchedFault controller_alarm_;
  LatchedFault summary_alarm_fault_;
  std::vector<bool> program_rejected_;  // per program: the controller refused its parameters
  bool alarm_reset_pending_ = false;

  Run run_;
  Kind refused_ = Kind::kNone;  // a loosen / manual run the controller did not start, until the ask changes
  bool has_done_ = false;
  std::uint32_t done_run_id_ = 0;  // the last planner tightening that ended
  int acked_program_ = -1;         // the program the controller last accepted
  LastResult last_;

  runtime::TextBuffer<160> blocked_by_;
  runtime::TextBuffer<160> reasons_text_;
  runtime::TextBuffer<80> alarms_text_;
  runtime::TextBuffer<40> selected_text_;
};

}  // namespace hubrt::tool_ecu
