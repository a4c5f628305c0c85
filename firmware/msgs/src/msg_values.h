// The value of a .msg constant checked and normalised as rosidl_adapter does
// (rosidl_adapter/parser.py, parse_primitive_value_string), for ros_msg.cc.
#pragma once

#include <string>
#include <string_view>

namespace hubrt::msgs::ros {

// Checks `text` (trimmed, after the '=') as a value of primitive `type` and returns it normalised
// (MsgConstant::value) in `out`. Returns an empty string when it is valid, else what is wrong
// ("must be a valid integer value >= 0 and <= 255"). Thread-safe.
std::string normalise_constant_value(std::string_view type, std::string_view text, std::string& out);

}  // namespace hubrt::msgs::ros
