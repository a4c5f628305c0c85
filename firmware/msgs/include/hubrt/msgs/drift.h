// Differences between a .msg and the IDL type idlc made of the IDL generated from it
// (msg_to_idl.h): the layout check of the generated IDL (test/idl_mapping_test.cc). The IDL side
// is taken from the reflection tables, i.e. from what idlc itself parsed and laid out, not from a
// second reading of the IDL text that could disagree with idlc.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "hubrt/msgs/ros_msg.h"
#include "hubrt/msgs/type_info.h"

namespace hubrt::msgs {

// The type of an IDL field written the way a .msg file writes it ("float32", "string[]",
// "hub_msgs/DockSlot", "int32[3]", "byte[<=4]"); struct types without a ROS name show their DDS
// name. Thread-safe.
std::string msg_type_of(const FieldInfo& field);

// Every difference between `msgs` and `idl_types`, one precise sentence each; empty when they
// agree. Compared: every IDL type must be ROS-named and have a .msg, and every .msg an IDL type
// (within the packages `msgs` covers; an IDL type of another package is reported as having no
// .msg package); per type, field count, names and order, and types — primitive, string bound,
// sequence / bounded sequence / array / single value, and nested type names
// (builtin_interfaces/Time <-> builtin_interfaces::msg::dds_::Time_); a .msg without fields
// matches rosidl's one placeholder member. Thread-safe.
std::vector<std::string> find_drift(std::span<const ros::MsgSpec> msgs,
                                    std::span<const TypeInfo* const> idl_types);

}  // namespace hubrt::msgs
