#include "tap_selection.h"

#include <algorithm>
#include <memory>
#include <set>

#include <fmt/format.h>

#include "conformance_target.h"  // is_state_type: the same test as hubctl conformance
#include "session.h"

namespace hubrt::hubctl {

bool is_command_type(const msgs::TypeInfo& type) noexcept {
  return type.ros_name.starts_with("hub_msgs/msg/") && type.ros_name.ends_with("Command");
}

bool is_state_topic(std::string_view /*ros_name*/, const msgs::TypeInfo& type) noexcept {
  return is_state_type(type);
}

bool is_station_traffic(std::string_view ros_name, const msgs::TypeInfo& type) noexcept {
  return is_state_type(type) || is_command_type(type) || ros_name == "/diagnostics" ||
         ros_name.starts_with("/sim/");
}

Expected<TapFilter> make_tap_filter(const TapChoice& choice) {
  std::set<std::string, std::less<>> names;
  for (const std::string& topic : choice.topics) {
    auto name = ros_topic(topic);
    if (!name) return std::move(name).error();
    names.insert(*name);
  }
  std::shared_ptr<const std::regex> pattern;
  if (!choice.regex.empty()) {
    try {
      pattern = std::make_shared<const std::regex>(choice.regex, std::regex::ECMAScript);
    } catch (const std::regex_error& e) {
      return make_error(ErrorCode::kInvalidArgument, fmt::format("--regex '{}': {}", choice.regex, e.what()));
    }
  }
  if (names.empty() && !pattern) {
    if (choice.all) return TapFilter([](std::string_view, const msgs::TypeInfo&) { return true; });
    return TapFilter(&is_station_traffic);
  }
  return TapFilter([names = std::move(names), pattern](std::string_view ros_name, const msgs::TypeInfo&) {
    if (names.count(ros_name) != 0) return true;
    return pattern && std::regex_match(ros_name.begin(), ros_name.end(), *pattern);
  });
}

}  // namespace hubrt::hubctl
