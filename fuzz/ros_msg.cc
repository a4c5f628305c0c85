// A ROS 2 .msg file through the one .msg parser of the tree (hubrt::msgs::ros::parse_msg), then
// through what reads its result: the IDL generator hubrt_msg2idl runs at build time
// (idl_from_msgs, with the file's nested types as defined elsewhere), and the comparison with the
// IDL type of the same name the layout check makes (find_drift).
// Input: the type's name on the first line ("DockState"), the file's text after it.
#include "hubrt/msgs/ros_msg.h"

#include <cstddef>
#include <cstdint>
#include <string>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/drift.h"
#include "hubrt/msgs/msg_to_idl.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  const auto newline = input.find('\n');
  if (newline == std::string_view::npos) return 0;
  const std::string name(input.substr(0, newline));
  auto spec = hubrt::msgs::ros::parse_msg(input.substr(newline + 1), "hub_msgs", name, "fuzz.msg");
  if (!spec) return 0;
  hubrt::msgs::IdlFileSpec file{"fuzz", {*spec}, {}};
  for (const auto& field : spec->fields) {
    (void)hubrt::msgs::ros::canonical_type(field);
    // Every nested type but the file's own is known from another IDL file: the generator writes
    // the whole file instead of stopping at the first unknown one.
    if (field.element_type.find('/') != std::string::npos) file.known[field.element_type] = "other";
  }
  if (auto idl = hubrt::msgs::idl_from_msgs(file);
      idl && idl->find("struct " + name + "_ {") == std::string::npos) {
    __builtin_trap();  // a generated file that lacks its own type
  }
  const hubrt::msgs::TypeInfo* type = hubrt::msgs::all_types().find("hub_msgs/msg/" + name);
  if (type == nullptr) return 0;
  const hubrt::msgs::TypeInfo* compared[] = {type};
  (void)hubrt::msgs::find_drift({&*spec, 1}, compared);
  return 0;
}
