#include "hubrt/hub_api/topic_names.h"

#include <fmt/format.h>

namespace hubrt::hub_api {

std::string node_command_topic(std::string_view ros_namespace, std::string_view node_type) {
  return fmt::format("{}/{}/command", ros_namespace, node_type);
}

std::string node_state_topic(std::string_view ros_namespace, std::string_view hub, std::string_view node) {
  return fmt::format("{}/{}/{}/state", ros_namespace, hub, node);
}

std::string hub_command_topic(std::string_view ros_namespace, std::string_view hub) {
  return fmt::format("{}/{}/command", ros_namespace, hub);
}

std::string hub_state_topic(std::string_view ros_namespace, std::string_view hub) {
  return fmt::format("{}/{}/state", ros_namespace, hub);
}

}  // namespace hubrt::hub_api
