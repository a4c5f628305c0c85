// The ROS 2 .msg text of every message type built into the program, and the complete definition
// of a type in rosbag2's "ros2msg" encoding: what MCAP files and the Foxglove WebSocket protocol
// carry as a schema, so that a reader decodes the CDR payloads without hubrt's types.
//
// The encoding (rosbag2, docs/message_definition_encoding.md; its MCAP storage plugin,
// rosbag2_storage_mcap/src/message_definition_cache.cpp): the type's own .msg text first; then each
// type it uses that was not written yet, depth-first, in the sorted order of the names as the .msg
// writes them (package resolved: "hub_msgs/DockSlot"), each preceded by "\n", a line of 80 '='
// and a line "MSG: <pkg>/<Type>".
#pragma once

#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"

namespace hubrt::msgs {

struct MsgDefinition {
  std::string_view ros_name;  // "hub_msgs/msg/DockState"
  std::string_view text;      // the .msg file as written, comments included
};

// Every definition built into the program, sorted by ros_name. Thread-safe.
std::span<const MsgDefinition> msg_definitions() noexcept;

// The .msg text of `ros_type`, named "pkg/msg/Type" or "pkg/Type"; nullopt when the program has no
// definition of it. Thread-safe.
std::optional<std::string_view> msg_text(std::string_view ros_type) noexcept;

// The complete definition of `ros_type` ("pkg/msg/Type" or "pkg/Type") in the "ros2msg" encoding.
// Errors: kNotFound naming the type, or the dependency, that has no definition;
// kInvalidArgument when a definition does not parse (the parser's located message). Thread-safe.
Expected<std::string> ros2msg_schema(std::string_view ros_type);

}  // namespace hubrt::msgs
