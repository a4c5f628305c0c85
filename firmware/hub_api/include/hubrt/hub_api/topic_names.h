// Topic names of the two layouts (paper §5.4), as ROS 2 topic names; the DDS layer adds "rt".
//   node-type layout: <ns>/<node_type>/command            one per node type, addressed by name
//                     <ns>/<hub>/<node>/state             one per node
//   hub layout:       <ns>/<hub>/command, <ns>/<hub>/state
//   everyone:         /diagnostics                        diagnostic_msgs/DiagnosticArray
#pragma once

#include <string>
#include <string_view>

namespace hubrt::hub_api {

std::string node_command_topic(std::string_view ros_namespace, std::string_view node_type);
std::string node_state_topic(std::string_view ros_namespace, std::string_view hub, std::string_view node);
std::string hub_command_topic(std::string_view ros_namespace, std::string_view hub);
std::string hub_state_topic(std::string_view ros_namespace, std::string_view hub);
inline constexpr std::string_view kDiagnosticsTopic = "/diagnostics";

}  // namespace hubrt::hub_api
