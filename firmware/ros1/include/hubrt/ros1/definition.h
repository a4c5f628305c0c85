// ROS 1 message definitions: what a ROS 1 publisher announces in its connection header
// (`message_definition`, `md5sum`, `type`), derived here from the ROS 2 .msg texts of the hub
// types (hubrt/msgs/definitions.h: those built into the program, the hub folders' msg/*.msg) so
// that the bridge knows, for every hub type, the one ROS 1 definition it accepts — with no file per
// type to keep in step.
//
// The ROS 1 forms follow genmsg (the ROS 1 message generator, python3-genmsg: gentools.py
// compute_md5_text / compute_full_text, msg_loader.py): the md5 text lists the constants
// ("type NAME=value") in file order, then the fields ("type name"), a nested message's type
// replaced by its own md5sum (arrays of messages too, without "[]"); the full definition is the
// main message's text, then per dependency (depth first, each once) a line of 80 '=', "MSG:
// pkg/Type" and its text.
#pragma once

#include <filesystem>
#include <map>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/msgs/definitions.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::ros1 {

struct Constant {
  std::string type;   // "uint8", "string"
  std::string name;   // "LIFECYCLE_SAFE"
  std::string value;  // as ROS 1 writes it: "2", "monitor" (strings unquoted)
};

struct Field {
  std::string type;   // resolved: "uint8", "string", "time", "hub_msgs/DockSlot", "std_msgs/Header"
  std::string array;  // "" (single value), "[]" (variable length) or "[N]" (fixed length)
  std::string name;

  [[nodiscard]] bool builtin() const;  // a primitive, time or duration (not a message)
  [[nodiscard]] std::string text() const { return type + array + " " + name; }
};

struct Message {
  std::string full_name;  // "hub_msgs/DockState"
  std::vector<Constant> constants;
  std::vector<Field> fields;
};

using Messages = std::map<std::string, Message, std::less<>>;  // by full name

// The ROS 1 name of a reflected type: "hub_msgs/msg/DockState" -> "hub_msgs/DockState".
std::string ros1_name_of(const msgs::TypeInfo& type);

// Parses one ROS 1 .msg text of message `full_name` ("pkg/Type"): bare message types resolve to
// pkg (a bare "Header" to std_msgs/Header). Errors (kInvalidArgument) name the line. Thread-safe.
Expected<Message> parse_ros1_msg(std::string_view text, std::string_view full_name);

// Parses a ROS 1 full definition (main text, then "MSG: pkg/Type" sections) announced for
// message `full_name`. Errors as parse_ros1_msg. Thread-safe.
Expected<Messages> parse_full_definition(std::string_view text, std::string_view full_name);

// The ROS 1 form of a ROS 2 .msg text of `full_name`: string and sequence bounds dropped (ROS 1
// has none; the bridge enforces them on the way in), "[<=N]" -> "[]", builtin_interfaces/Time and
// Duration -> time and duration, string constants unquoted, default values dropped. Thread-safe.
Expected<Message> ros1_from_ros2_msg(std::string_view text, std::string_view full_name);

// Every <root>/<pkg>/msg/*.msg (a ROS 2 interface tree) in its ROS 1 form.
// Errors: kNotFound for a missing root, parse errors naming file and line.
Expected<Messages> load_ros2_tree_as_ros1(const std::filesystem::path& root);

// Every hub_msgs definition of `definitions` (msgs::msg_definitions(): the .msg texts built into
// the program) in its ROS 1 form. The standard ROS 2 types there are left out: builtin_interfaces
// maps to ROS 1's time and duration, and ROS 1 has std_msgs of its own. Errors: parse errors
// naming the type and line. Thread-safe.
Expected<Messages> load_definitions_as_ros1(std::span<const msgs::MsgDefinition> definitions);

// The ROS 1 .msg text of one message (constants, then fields; no comments).
std::string msg_text(const Message& message);

// The full definition of `full_name` as a ROS 1 publisher announces it; md5sum as genmsg computes
// it. Errors: kNotFound naming the first message type `messages` lacks. Thread-safe.
Expected<std::string> full_definition(const Messages& messages, std::string_view full_name);
Expected<std::string> md5sum(const Messages& messages, std::string_view full_name);

// The first difference between the definition the bridge expects and the one a ROS 1 peer
// announced for `full_name`, following nested messages, as one sentence naming the field
// ("hub_msgs/DockState.slots: ..."); empty when they agree. Thread-safe.
std::string first_difference(const Messages& expected, const Messages& announced, std::string_view full_name);

// Checks that ROS 1 message `full_name` has the layout of reflected type `type`, field by field
// and nested, so that codec.h's encoding is that definition's. Errors (kInvalidArgument) name the
// field. Thread-safe.
Expected<void> check_matches(const Messages& messages, std::string_view full_name,
                             const msgs::TypeInfo& type);

}  // namespace hubrt::ros1
