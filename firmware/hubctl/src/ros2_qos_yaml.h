// The offered QoS of a topic's writers as rosbag2 keeps it in an MCAP channel's metadata
// ("offered_qos_profiles"; MCAP spec registry.md, profile ros2): a YAML sequence of profiles with
// policy names (rosbag2_storage/src/rosbag2_storage/qos.cpp, convert<rclcpp::QoS>::encode, metadata
// version 9 and later). Infinite durations are rmw's RMW_DURATION_INFINITE, {9223372036, 854775807}.
#pragma once

#include <string>
#include <vector>

#include "hubrt/dds/qos.h"

namespace hubrt::hubctl {

// The text for `offered` ("[]\n" for none), as yaml-cpp's Dump of rosbag2's node writes it.
// Thread-safe.
std::string offered_qos_yaml(const std::vector<dds::OfferedQos>& offered);

// The profiles of such a text, numbers of older rosbag2 versions (history: 1) accepted too. What
// is missing reads as the DDS default; a text that is not such YAML gives no profiles (the caller
// falls back to its default QoS). Never throws; thread-safe.
std::vector<dds::OfferedQos> parse_offered_qos_yaml(const std::string& text);

}  // namespace hubrt::hubctl
