// The tool-changer node's settings in the hub file: which board signals it uses, the names of the
// tools on the tool-ID lines, and the pneumatic timing it supervises.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_requirements.h"

namespace hubrt::rsp_ecu {

struct ToolLine {
  std::string tool;    // reported in State.tool and looked up as a Dock ECU slot, e.g. "smart_tool"
  std::string signal;  // board input, e.g. "rsp.tool_id.smart_tool"
};

struct RspSettings {
  static constexpr std::size_t kMaxTools = 8;

  std::string dock_subscription;                // the hub file's subscription giving the Dock ECU State
  std::string lock_valve;                       // output: energised = changer open
  std::string gripper_valve;                    // output: energised = gripper closed (grab)
  std::vector<ToolLine> tool_lines;             // 1..kMaxTools, one line per tool
  std::array<std::string, 2> gripper_confirms;  // inputs: active = gripper closed
  std::string pressure_switch;                  // input: active = supply pressure OK
  std::string gripper_tool;    // the tool that carries the gripper (its confirms are supervised)
  Duration lock_actuation{};   // a lock stroke takes at most this long (the lock has no sensor)
  Duration gripper_confirm{};  // the confirms must follow the gripper valve within this
};

// Reads and checks a node's settings (keys: type, dock, lock_valve, gripper_valve, tool_id,
// gripper_confirm, pressure_switch, gripper_tool, lock_actuation_ms, gripper_confirm_ms). Tool
// names are ROS name tokens, unique, not "none" or "undefined"; gripper_tool is one of them.
// Errors name file:line, the key and the problem. Not thread-safe (yaml-cpp); allocates.
Expected<RspSettings> parse_rsp_settings(const config::NodeConfig& node);

// Adds the signals the node uses to `requirements`.
void add_requirements(const RspSettings& settings, hal::BoardRequirements& requirements);

}  // namespace hubrt::rsp_ecu
