// The DDS IDL of ROS 2 .msg files, as ROS 2 puts them on the wire: what idlc and the reflection
// plugin read (firmware/msgs/README.md, "One source: the .msg"). The mapping is rosidl's:
// rosidl_adapter (rosidl_adapter/msg/__init__.py: MSG_TYPE_TO_IDL, get_idl_type; resource/
// msg.idl.em, struct.idl.em) takes .msg to IDL — bool -> boolean, byte -> octet, char -> uint8,
// float32/64 -> float/double, string<=N -> string<N>, T[] -> sequence<T>, T[<=N] -> sequence<T, N>,
// a nested pkg/Type -> its struct, constants in a module <Type>_Constants, a message without fields
// gets `uint8 structure_needs_at_least_one_member` — and rosidl_generator_dds_idl (resource/
// msg.idl.em, idl_typename) puts each type in `module dds_` named `<Type>_`, fixed-size arrays as
// declarators `T name[N]`, the names rmw_cyclonedds also uses on the wire. Every struct is @final
// (XCDR1, not appendable, as every ROS 2 RMW).
#pragma once

#include <map>
#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/msgs/ros_msg.h"

namespace hubrt::msgs {

// One generated IDL file: <stem>.idl holding `messages`.
struct IdlFileSpec {
  std::string stem;                          // "dock": dock.idl, included as "dock.idl"
  std::vector<ros::MsgSpec> messages;        // any order: each is written after what it uses
  std::map<std::string, std::string> known;  // "pkg/Type" -> stem of the IDL file defining it
};

// The text of <stem>.idl. Errors (kInvalidArgument), each naming the .msg file and line: a nested
// type that is neither in `messages` nor `known`; messages that contain each other; what the
// generated C types cannot carry: a default value (idlc's C generator ignores @default: a hub
// would start from zeros where a ROS 2 node starts from the default), a wstring (the reflection
// tables have no wide strings), a string constant with '"', '\' or a byte outside printable ASCII
// (idlc 0.10 writes string constants into its C header unescaped). Thread-safe.
Expected<std::string> idl_from_msgs(const IdlFileSpec& file);

}  // namespace hubrt::msgs
