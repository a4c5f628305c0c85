// The bridge file: which static one-directional bridges one hubbridge process runs
// (docs/ros1-bridge.md). Each bridge is one topic, one type, one direction.
#pragma once

#include <string>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::hubbridge {

enum class Direction : std::uint8_t { kRos1ToDds, kDdsToRos1 };
enum class Reliability : std::uint8_t { kReliable, kBestEffort };

struct BridgeConfig {
  std::string ros1_topic;  // "/dock_ecu/dock/state"
  std::string dds_topic;   // ROS 2 name, "/dock_ecu/dock/state" (DDS "rt/dock_ecu/dock/state")
  std::string type;        // "hub_msgs/DockState" (or "hub_msgs/msg/DockState")
  Direction direction = Direction::kRos1ToDds;
  Reliability reliability = Reliability::kReliable;
  int depth = 10;      // DDS history depth and ROS 1 queue size
  bool latch = false;  // dds_to_ros1 only: ROS 1 latched publisher
};

struct BridgeFile {
  std::string name;       // the hub it stands for: DDS participant name, ROS 1 node, /diagnostics prefix
  std::string msg_dir;    // ROS 2 interface tree (contains hub_msgs/msg/*.msg), resolved; empty:
                          // the .msg texts built into hubbridge (hubrt/msgs/definitions.h)
  double silent_after_s;  // ros1_to_dds: no sample for this long -> "silent" on /diagnostics
  // After a rosmaster restart, register the ROS 1 nodes this bridge is connected to with the new
  // master on their behalf (master_sync.h); false: only hubbridge's own endpoints.
  bool register_lost_publishers = true;
  std::vector<BridgeConfig> bridges;
};

// Reads the bridge file. `msg_dir` (optional) is resolved relative to the file. Errors name file:line and
// the key: unknown keys, a missing or repeated topic in one direction, invalid ROS names.
Expected<BridgeFile> load_bridge_file(const std::string& path);

// Same, from text (tests); `name` stands for the file name, relative paths resolve against
// `base_dir`.
Expected<BridgeFile> load_bridge_text(const std::string& text, const std::string& name,
                                      const std::string& base_dir);

}  // namespace hubrt::hubbridge
