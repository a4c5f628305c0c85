// The generated IDL, as idlc compiled it, holds what each .msg says: every registered type against
// its .msg text (the texts built into the program with the message targets, hubrt/msgs/definitions.h)
// field by field — names, order, primitive types, string bounds, arrays, bounded and unbounded
// sequences, nested types (find_drift) — and the fixture of every shape likewise, with its
// constants as idlc's C header defines them.
#include <algorithm>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/definitions.h"
#include "hubrt/msgs/drift.h"
#include "hubrt/msgs/ros_msg.h"

#include "builtin_interfaces_reflect.h"
#include "shapes.h"
#include "shapes_reflect.h"

namespace hubrt::msgs {
namespace {

// "pkg/msg/Type" -> its parsed text.
ros::MsgSpec parsed(const MsgDefinition& definition) {
  const std::string name(definition.ros_name);
  auto spec = ros::parse_msg(definition.text, name.substr(0, name.find('/')),
                             name.substr(name.rfind('/') + 1), name + ".msg");
  EXPECT_TRUE(spec) << spec.error().message;
  return spec ? *spec : ros::MsgSpec{};
}

std::string report(const std::vector<std::string>& drift) {
  std::string out;
  for (const auto& sentence : drift) out += "  - " + sentence + "\n";
  return out;
}

TEST(IdlMapping, EveryRegisteredTypeIsItsMsgFieldByField) {
  std::vector<ros::MsgSpec> msgs;
  for (const MsgDefinition& definition : msg_definitions()) msgs.push_back(parsed(definition));
  // Guard against a vacuous pass: the hubs' types, the common and the standard ones are there.
  for (const char* name : {"hub_msgs/msg/DockState", "hub_msgs/msg/StateHeader", "hub_msgs/msg/SimSignals",
                           "diagnostic_msgs/msg/DiagnosticArray", "builtin_interfaces/msg/Time"}) {
    EXPECT_NE(all_types().find(name), nullptr) << name;
    EXPECT_TRUE(std::any_of(msgs.begin(), msgs.end(), [&](const auto& m) { return m.ros_name() == name; }))
        << name;
  }
  const auto drift = find_drift(msgs, all_types().types());
  EXPECT_TRUE(drift.empty()) << "the generated IDL does not hold what the .msg says:\n" << report(drift);
}

TEST(IdlMapping, TheFixtureOfEveryShapeIsItsMsgFieldByField) {
  std::vector<ros::MsgSpec> msgs;
  for (const char* name : {"Shapes", "Part", "Empty"}) {
    const std::string path = std::string(HUBRT_MSG_FIXTURE_DIR) + "/" + name + ".msg";
    std::ifstream in(path, std::ios::binary);
    ASSERT_TRUE(in.is_open()) << path;
    std::ostringstream text;
    text << in.rdbuf();
    auto spec = ros::parse_msg(text.str(), "msg_fixture", name, path);
    ASSERT_TRUE(spec) << spec.error().message;
    msgs.push_back(*spec);
  }
  auto time = ros::parse_msg("int32 sec\nuint32 nanosec\n", "builtin_interfaces", "Time", "Time.msg");
  ASSERT_TRUE(time);
  msgs.push_back(*time);
  std::vector<const TypeInfo*> types(reflected::types_of_shapes().begin(),
                                     reflected::types_of_shapes().end());
  types.push_back(&type_info_of<builtin_interfaces_msg_dds__Time_>());
  ASSERT_EQ(types.size(), 4U);
  const auto drift = find_drift(msgs, types);
  EXPECT_TRUE(drift.empty()) << report(drift);
  // The placeholder member of a message without fields (rosidl's rule) is all its IDL has.
  const TypeInfo& empty = type_info_of<msg_fixture_msg_dds__Empty_>();
  ASSERT_EQ(empty.fields.size(), 1U);
  EXPECT_EQ(empty.fields[0].name, "structure_needs_at_least_one_member");
}

// module Shapes_Constants { const ... } inside module dds_: idlc defines each as
// <pkg>_msg_dds__<Type>_Constants_<NAME>, with the value the .msg gives.
TEST(IdlMapping, TheFixtureConstantsReachTheCTypesWithTheirValues) {
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_FLAG, true);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_BYTE_MAX, 255);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_LETTER, 65);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_HALF, 0.5);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_HUGE, 1e300);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_INT8_MIN, -128);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_UINT8_MAX, 255);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_INT16_MIN, -32768);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_UINT16_MAX, 65535);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_INT32_MIN, -2147483648LL);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_UINT32_MAX, 4294967295ULL);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_INT64_LOW, -9223372036854775807LL);
  EXPECT_EQ(msg_fixture_msg_dds__Shapes_Constants_UINT64_BIG, 4294967296ULL);
  EXPECT_STREQ(msg_fixture_msg_dds__Shapes_Constants_GREETING, "hello # not a comment");
  EXPECT_STREQ(msg_fixture_msg_dds__Shapes_Constants_QUOTED, "it's");
  EXPECT_STREQ(msg_fixture_msg_dds__Shapes_Constants_BARE, "plain text");
}

}  // namespace
}  // namespace hubrt::msgs
