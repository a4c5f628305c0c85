// The Tool ECU nodes' settings in the hub file: which board signals, bus and device they use,
// the tightening programs, the lift's named positions and the supervision times.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_requirements.h"
#include "hubrt/protocol/smart_tool_can.h"

namespace hubrt::tool_ecu {

// A tightening program the planner names in a "tighten" command.
struct ToolProgram {
  std::string name;  // e.g. "ladder_frame_bolt"
  protocol::smart_tool::Program program;
};

struct ArmSignals {
  std::string home = "tool.arm.home";
  std::string pre_home = "tool.arm.pre_home";
  std::string out_of_range = "tool.arm.out_of_range";
};

struct SmartToolSettings {
  static constexpr std::size_t kMaxPrograms = 32;

  std::string bus = "tool_bus";  // board CAN bus of the controller
  std::uint8_t node_id = protocol::smart_tool::kDefaultNodeId;
  std::string run_forward = "tool.run_forward";
  std::string run_reverse = "tool.run_reverse";
  std::string button_forward = "tool.button.forward";
  std::string button_reverse = "tool.button.reverse";
  std::string torque_reached = "tool.torque_reached";
  std::string summary_alarm = "tool.summary_alarm";
  ArmSignals arm;
  std::string robot_state = "rsp";  // the hub file's subscription giving the RSP ECU's RspState
  // The hub file's subscription giving the operator hub's OperatorPanelState; empty: no operator
  // interlock (a cell without an operator hub). Set: tighten only while an operator is verified.
  std::string operator_state;
  std::vector<ToolProgram> programs;  // 1..kMaxPrograms, names and numbers unique
  int manual_program = -1;            // index into programs for the handle's forward button; -1: none
  // A Start the controller has not confirmed (status: running, run counter + 1) within this is
  // taken as refused.
  Duration start_timeout = std::chrono::milliseconds(500);
  // A program select or Stop not acknowledged within this is sent again.
  Duration resend_after = std::chrono::milliseconds(300);
};

struct LiftPosition {
  std::string name;            // e.g. "home", "float", "work"
  std::uint16_t tenth_mm = 0;  // the drive's unit
};

struct LiftSettings {
  static constexpr std::size_t kMaxPositions = 16;

  std::string device = "lift_drive";    // board Modbus device
  std::vector<LiftPosition> positions;  // 1..kMaxPositions, names unique
  std::uint16_t speed_mm_s = 100;
  // Written to the drive's communication watchdog: the drive faults and stops by itself when the
  // hub stops talking for this long. 0 = off.
  std::uint16_t drive_watchdog_ms = 1000;
  // The drive counts as not answering when no exchange succeeded for this long.
  Duration answer_within = std::chrono::milliseconds(500);
  // Least time between two requests to the drive (at most one per cycle; one in flight at a time).
  Duration poll_interval = std::chrono::milliseconds(20);
};

// Read and check a node's settings. Errors name file:line, the key and the problem.
// Not thread-safe (yaml-cpp); allocates.
//   smart_tool keys: type, bus, node_id, signals {run_forward, run_reverse, button_forward,
//     button_reverse, torque_reached, summary_alarm, arm_home, arm_pre_home, arm_out_of_range},
//     robot_state, programs {name: {number, torque_nm, angle_min_deg, angle_max_deg}},
//     manual_program, start_timeout_ms, resend_ms
//   lift keys: type, device, positions {name: mm}, speed_mm_s, drive_watchdog_ms,
//     answer_within_ms, poll_ms
Expected<SmartToolSettings> parse_smart_tool_settings(const config::NodeConfig& node);
Expected<LiftSettings> parse_lift_settings(const config::NodeConfig& node);

// Add the signals, bus and device the node uses to `requirements`.
void add_requirements(const SmartToolSettings& settings, hal::BoardRequirements& requirements);
void add_requirements(const LiftSettings& settings, hal::BoardRequirements& requirements);

}  // namespace hubrt::tool_ecu
