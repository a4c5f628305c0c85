// ROS 2 .msg files: the one source of every message type (the IDL is generated from them,
// msg_to_idl.h), read also for the schemas of recordings (definitions.h) and the layout check
// (drift.h). ROS 2 itself is not available on the hubs' build machines and no C++ library parses
// .msg, so this is a small parser of the documented grammar (rosidl_adapter/parser.py:
// parse_message_string, parse_primitive_value_string): "TYPE NAME [DEFAULT]" fields, "TYPE
// NAME=VALUE" constants, '#' comments; TYPE is a primitive, "string<=N", "Type" or "pkg/Type",
// optionally followed by "[]", "[N]" or "[<=N]".
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"

namespace hubrt::msgs::ros {

enum class Container : std::uint8_t { kNone, kSequence, kBoundedSequence, kArray };

struct MsgField {
  // Element type with its package resolved: a primitive ("float32", "byte", "string") or
  // "pkg/Type" (a bare "Type" means the file's own package).
  std::string element_type;
  std::uint32_t string_bound = 0;  // N of "string<=N"; 0 for unbounded strings and other types
  Container container = Container::kNone;
  std::uint32_t bound = 0;  // N of "[N]" or "[<=N]"
  std::string name;
  std::string default_value;  // the text after the name, as written; empty when there is none
  int line = 0;               // 1-based line in the file
};

// "TYPE NAME=VALUE": part of the generated code, not of the wire layout. The value is checked as
// rosidl_adapter checks it (parse_primitive_value_string) and kept normalised: integers in
// decimal, bool "true"/"false", floats as written, strings without their quotes (an escaped quote
// of the quoting kind unescaped).
struct MsgConstant {
  std::string type;  // a primitive without bound or array: "uint8", "string"
  std::string name;  // UPPER_CASE
  std::string value;
  int line = 0;
};

struct MsgSpec {
  std::string package;                 // "hub_msgs"
  std::string name;                    // "DockState"
  std::string file;                    // where it came from, for messages
  std::vector<MsgField> fields;        // in file order; constants are not fields (not on the wire)
  std::vector<MsgConstant> constants;  // in file order

  // "hub_msgs/msg/DockState"
  [[nodiscard]] std::string ros_name() const { return package + "/msg/" + name; }
};

// The field's type written the canonical .msg way: "float32", "string<=8", "hub_msgs/DockSlot[]",
// "int32[3]", "byte[<=4]".
std::string canonical_type(const MsgField& field);

// Parses the text of <package>/msg/<name>.msg. `file` names it in messages. Errors
// (kInvalidArgument) read "<file>:<line>: <what is wrong>". Thread-safe.
Expected<MsgSpec> parse_msg(std::string_view text, std::string package, std::string name, std::string file);

// Every <root>/<package>/msg/*.msg, sorted by package and name. kNotFound when `root` does not
// exist; parse errors as parse_msg(). Thread-safe.
Expected<std::vector<MsgSpec>> load_msg_packages(const std::filesystem::path& root);

}  // namespace hubrt::msgs::ros
