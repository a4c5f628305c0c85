// A ROS 2 .msg file through the parser the drift check uses (hubrt::msgs::ros::parse_msg), then
// compared with the IDL type of the same name, as FindDrift does for ros2/hub_msgs.
// Input: the type's name on the first line ("DockState"), the file's text after it.
#include "hubrt/msgs/ros_msg.h"

#include <cstddef>
#include <cstdint>
#include <string>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/drift.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const auto newline = input.find('\n');
  if (newline == std::string_view::npos) return 0;
  const std::string name(input.substr(0, newline));
  auto spec = hubrt::msgs::ros::parse_msg(input.substr(newline + 1), "hub_msgs", name, "fuzz.msg");
  if (!spec) return 0;
  for (const auto& field : spec->fields) (void)hubrt::msgs::ros::canonical_type(field);
  const hubrt::msgs::TypeInfo* type = hubrt::msgs::all_types().find("hub_msgs/msg/" + name);
  if (type == nullptr) return 0;
  const hubrt::msgs::TypeInfo* compared[] = {type};
  (void)hubrt::msgs::find_drift({&*spec, 1}, compared);
  return 0;
}
