// ROS 2 names on the DDS wire: topic "/dock/command" is DDS topic "rt/dock/command"; message type
// "hub_msgs/msg/DockCommand" is DDS type "hub_msgs::msg::dds_::DockCommand_" (the descriptor's
// m_typename). All functions are pure and thread-safe.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"

namespace hubrt::dds {

// Checks a fully qualified ROS 2 topic name: starts with '/', only letters, digits, '_' and '/',
// no empty segment ("//"), no trailing '/', no segment starting with a digit.
// Errors: kInvalidArgument with a message quoting the name and naming the rule it breaks.
Expected<void> validate_ros_topic_name(std::string_view ros_name);

// "/dock/command" -> "rt/dock/command". Errors: those of validate_ros_topic_name().
Expected<std::string> ros_to_dds_topic(std::string_view ros_name);

// "rt/dock/command" -> "/dock/command"; nullopt for DDS topics that are not ROS 2 topics
// (no "rt/" prefix: services, builtin or foreign topics).
std::optional<std::string> dds_to_ros_topic(std::string_view dds_name);

// "hub_msgs::msg::dds_::DockCommand_" -> "hub_msgs/msg/DockCommand".
// Errors: kInvalidArgument when the name is not of the form <pkg>::<msg|srv|action>::dds_::<Type>_.
Expected<std::string> dds_to_ros_type(std::string_view dds_type_name);

// "hub_msgs/msg/DockCommand" -> "hub_msgs::msg::dds_::DockCommand_".
// Errors: kInvalidArgument when the name is not of the form <pkg>/<msg|srv|action>/<Type>.
Expected<std::string> ros_to_dds_type(std::string_view ros_type_name);

}  // namespace hubrt::dds
