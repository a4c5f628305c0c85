// The Dock ECU's messages for a Fast DDS planner (fastdds_planner.h), in both layouts: the
// node-type layout (DockCommand on /dock/command, DockState on /dock_ecu/dock/state) and the hub
// layout (DockEcuCommand on /dock_ecu/command, DockEcuState on /dock_ecu/state). Types from
// fastddsgen over the .msg files of ros2/hub_msgs.
#pragma once

#include <chrono>
#include <string>

#include "fastdds_planner.h"
#include "hub_msgs_plain.h"
#include "hub_msgs_plainPubSubTypes.h"

namespace hubrt::interop {

struct DockNodeTypes {
  using Command = hub_msgs::msg::DockCommand;
  using CommandPubSubType = hub_msgs::msg::DockCommandPubSubType;
  using State = hub_msgs::msg::DockState;
  using StatePubSubType = hub_msgs::msg::DockStatePubSubType;
  // ROS 2's names on the wire: topic "rt/<topic>" (types: hub_msgs::msg::dds_::<Type>_).
  static constexpr const char* kCommandTopic = "rt/dock/command";
  static constexpr const char* kStateTopic = "rt/dock_ecu/dock/state";
};

struct DockEcuHubTypes {
  using Command = hub_msgs::msg::DockEcuCommand;
  using CommandPubSubType = hub_msgs::msg::DockEcuCommandPubSubType;
  using State = hub_msgs::msg::DockEcuState;
  using StatePubSubType = hub_msgs::msg::DockEcuStatePubSubType;
  static constexpr const char* kCommandTopic = "rt/dock_ecu/command";
  static constexpr const char* kStateTopic = "rt/dock_ecu/state";
};

// Generous: a busy 2-core machine running sanitizer builds of several test programs at once
// (hubd start-up and discovery take seconds there). These tests check behaviour; the benchmarks
// measure timing.
inline constexpr std::chrono::milliseconds kPatience{20000};
// A planner repeats its command well within the Dock ECU's command timeout (1000 ms); the
// station's planner runs at 10 Hz.
inline constexpr std::chrono::milliseconds kCommandPeriod{50};

using FastDdsDockPlanner = FastDdsPlanner<DockNodeTypes>;
using FastDdsDockEcuPlanner = FastDdsPlanner<DockEcuHubTypes>;
using ReceivedState = FastDdsDockPlanner::ReceivedState;

// Every text in a State's error_list, joined with "; " (for searching and failure messages).
std::string joined_errors(const std::vector<eprosima::fastrtps::fixed_string<191>>& error_list);
template <class State>
std::string joined_errors(const State& state) {
  return joined_errors(state.error_list());
}

// A command as ROS 2 code writes it.
hub_msgs::msg::DockCommand dock_command(const std::string& target_type, const std::string& target_name,
                                        const std::string& action);

}  // namespace hubrt::interop
