// JSON <-> sample for one "slot": a whole field, or one element of a sequence or array (described
// by element_slot()). Shared by from_json()/to_json() and set_field(). Assignment is split in a
// check that may fail and an assign that cannot, so that failures leave the sample untouched.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

#include "hubrt/base/status.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::msgs::detail {

using Json = nlohmann::ordered_json;

// A FieldInfo describing one element of a kSequence or kArray field (kind == element kind).
FieldInfo element_slot(const FieldInfo& container);

// The field called `name`, or nullptr.
const FieldInfo* find_field(const TypeInfo& type, std::string_view name);
// kInvalidArgument: `path` names no field of `type`; suggests close names and lists the fields.
Error unknown_field(const TypeInfo& type, std::string_view name, std::string_view path);

// Name of a type for messages: its ROS name, else its DDS name.
std::string_view display_name(const TypeInfo& type);

Json slot_to_json(const FieldInfo& slot, const void* addr);
// See msgs::invalid_utf8_fields().
std::vector<std::string> invalid_utf8_fields(const TypeInfo& type, const void* sample);
Json struct_to_json(const TypeInfo& type, const void* addr);

// `path` is the dotted path of the slot, used in messages.
Expected<void> check_slot_json(const FieldInfo& slot, const Json& value, const std::string& path);
Expected<void> check_struct_json(const TypeInfo& type, const Json& value, const std::string& path);
// Precondition: the matching check_* accepted `value`.
void assign_slot_json(const FieldInfo& slot, const Json& value, void* addr);
void assign_struct_json(const TypeInfo& type, const Json& value, void* addr);

// Short rendering of a JSON value for messages: "'abc'", "3.5", "an object".
std::string describe_json(const Json& value);

}  // namespace hubrt::msgs::detail
