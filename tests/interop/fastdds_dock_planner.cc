#include "fastdds_dock_planner.h"

namespace hubrt::interop {

std::string joined_errors(const std::vector<eprosima::fastrtps::fixed_string<191>>& error_list) {
  std::string out;
  for (const auto& error : error_list) out += error.to_string() + "; ";
  return out;
}

hub_msgs::msg::DockCommand dock_command(const std::string& target_type, const std::string& target_name,
                                        const std::string& action) {
  hub_msgs::msg::DockCommand command;
  command.target_type(target_type);
  command.target_name(target_name);
  command.action(action);
  return command;
}

}  // namespace hubrt::interop
