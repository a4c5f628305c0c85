// The station description hubsim reads (hubs/station/station.yaml): which hubs make the station,
// where the robot can go, which end-effectors there are and which signals tell about them.
// Documented in hubs/station/README.md.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/config/yaml_map.h"

namespace hubrt::sim::station {

// The three hubs the station couples, by what they do.
enum class HubRole : std::uint8_t { kTool = 0, kRsp = 1, kDock = 2 };
inline constexpr std::size_t kHubRoles = 3;
// "tool_ecu", "rsp_ecu", "dock_ecu": the hub type, and the default instance name.
std::string_view to_string(HubRole role) noexcept;

// An end-effector: its name is also its dock slot's name, the RSP's tool name and the name of
// the place in front of its slot where the robot goes to take or leave it.
struct ToolConfig {
  std::string name;            // e.g. "smart_tool"
  std::string tool_id_signal;  // RSP ECU input: the tool is on the changer
  std::string dock_signal;     // Dock ECU input: the tool sits in its slot
  bool starts_on_robot = false;
};

// The mobile platform (a MiR100 driven by the mir_com hub) that brings the kit with the ladder
// frame and takes it away. hubsim reads its State: the kit is at the station while the platform
// stands at `at_station`.
struct MobilePlatformConfig {
  std::string state_topic;  // e.g. "/mir_com/mover/state"
  // "": state_topic carries a RobotMoverState (node-type layout); else the hub layout's
  // MirComState, whose field of this name is the mover's State.
  std::string field;
  std::string at_station;                              // the platform's position (actual_pose) at the station
  std::string kit = "kit";                             // the robot's place that is the kit on the platform
  Duration timeout = std::chrono::milliseconds(1000);  // no State for this long: platform unknown
};

struct StationConfig {
  std::string file;
  std::array<std::string, kHubRoles> hubs{"tool_ecu", "rsp_ecu", "dock_ecu"};  // instance names
  double rate_hz = 50.0;
  Duration resend_holdoff = std::chrono::milliseconds(250);  // before an input is sent again

  // The robot: the places it can go besides the dock slots, where it starts, how long a move takes.
  std::vector<std::string> places{"home", "kit", "engine"};
  std::string robot_start = "home";
  Duration robot_travel = std::chrono::milliseconds(300);

  // The tool changer's valves on the RSP ECU (their simulated actuators' positions).
  std::string lock_valve = "rsp.lock_valve";        // energised = changer open
  std::string gripper_valve = "rsp.gripper_valve";  // energised = gripper closed

  std::vector<ToolConfig> tools;

  // The ladder frame: which end-effector's gripper holds it, where it lies at the start, where it
  // may be put down (elsewhere it drops).
  std::string frame_tool = "ladder_frame_tool";
  std::string frame_start = "kit";
  std::vector<std::string> frame_rests{"kit", "engine"};

  // The smart tool's arm sensors (Tool ECU inputs), from where the tool is: in its holder on the
  // lift, high = home, a little lower = pre-home, lower = operating (floating above the engine);
  // on the robot at `operating_at` = operating, at its slot (the holder) = as in the holder,
  // elsewhere = out of range.
  std::string arm_tool = "smart_tool";
  std::string lift_device = "lift_drive";
  std::string arm_home_signal = "tool.arm.home";
  std::string arm_pre_home_signal = "tool.arm.pre_home";
  std::string arm_out_of_range_signal = "tool.arm.out_of_range";
  double home_above_mm = 370.0;
  double pre_home_above_mm = 330.0;
  std::string operating_at = "engine";

  // Absent: the kit is always at the station.
  std::optional<MobilePlatformConfig> mobile_platform;

  [[nodiscard]] const ToolConfig* find_tool(std::string_view name) const noexcept;
  // A place or a dock slot.
  [[nodiscard]] bool is_location(std::string_view name) const noexcept;
};

// Loads and checks a station description. Errors name file:line:col, the key and the problem:
// unknown keys, names that are not identifiers, a tool named like a place, references to tools or
// places that do not exist, more than one tool starting on the robot, thresholds out of order,
// a mobile platform section with unknown keys, a topic that is not a ROS topic name, an empty
// position or one longer than RobotMoverState's actual_pose (64 bytes), a field not of MirComState.
Expected<StationConfig> load_station_config(const std::string& path);
Expected<StationConfig> parse_station_config(const config::YamlMap& root);

}  // namespace hubrt::sim::station
