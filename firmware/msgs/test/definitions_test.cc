// The .msg definitions built into a program and the "ros2msg" schemas made from them: what MCAP
// recordings and the Foxglove live view send as schemas (hubrt/msgs/definitions.h).
#include "hubrt/msgs/definitions.h"

#include <string>
#include <string_view>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"

namespace hubrt::msgs {
namespace {

// The "MSG: <name>" delimiter lines of a schema, in order.
std::vector<std::string> delimited_names(std::string_view schema) {
  std::vector<std::string> names;
  const std::string marker = std::string(80, '=') + "\nMSG: ";
  for (std::size_t at = schema.find(marker); at != std::string_view::npos; at = schema.find(marker, at + 1)) {
    const std::size_t begin = at + marker.size();
    names.emplace_back(schema.substr(begin, schema.find('\n', begin) - begin));
  }
  return names;
}

TEST(MsgDefinitions, EveryRegisteredRosTypeHasADefinitionAndASchema) {
  std::size_t checked = 0;
  for (const TypeInfo* type : all_types().types()) {
    if (type->ros_name.empty()) continue;
    SCOPED_TRACE(std::string(type->ros_name));
    EXPECT_TRUE(msg_text(type->ros_name).has_value());
    const Expected<std::string> schema = ros2msg_schema(type->ros_name);
    ASSERT_TRUE(schema.is_ok()) << schema.error().message;
    EXPECT_EQ(schema->substr(0, msg_text(type->ros_name)->size()), *msg_text(type->ros_name));
    ++checked;
  }
  EXPECT_GT(checked, 30U);  // every hub's Command and State, the sim's and the common types
}

TEST(MsgDefinitions, TableIsSortedAndUnique) {
  const auto all = msg_definitions();
  for (std::size_t i = 1; i < all.size(); ++i) EXPECT_LT(all[i - 1].ros_name, all[i].ros_name);
}

// rosbag2's order: the type's own text, then the types it uses sorted by name, each followed at
// once by what it uses in turn (StateHeader's Time right after StateHeader), each written once.
TEST(MsgDefinitions, SchemaAppendsDependenciesDepthFirstInSortedOrderOnce) {
  const Expected<std::string> schema = ros2msg_schema("hub_msgs/msg/DockState");
  ASSERT_TRUE(schema.is_ok()) << schema.error().message;
  EXPECT_EQ(delimited_names(*schema),
            (std::vector<std::string>{"hub_msgs/DockCommand", "hub_msgs/DockSlot", "hub_msgs/StateHeader",
                                      "builtin_interfaces/Time"}));
  // Each delimiter starts a line of its own, after the previous text and a newline.
  const std::string delimiter = "\n" + std::string(80, '=') + "\nMSG: hub_msgs/DockSlot\n";
  const std::size_t at = schema->find(delimiter);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(schema->substr(at + delimiter.size(), msg_text("hub_msgs/DockSlot")->size()),
            *msg_text("hub_msgs/DockSlot"));
}

TEST(MsgDefinitions, DiagnosticArrayUsesTheStandardTypes) {
  const Expected<std::string> schema = ros2msg_schema("diagnostic_msgs/DiagnosticArray");
  ASSERT_TRUE(schema.is_ok()) << schema.error().message;
  EXPECT_EQ(delimited_names(*schema),
            (std::vector<std::string>{"diagnostic_msgs/DiagnosticStatus", "diagnostic_msgs/KeyValue",
                                      "std_msgs/Header", "builtin_interfaces/Time"}));
}

TEST(MsgDefinitions, ShortAndFullNamesFindTheSameText) {
  ASSERT_TRUE(msg_text("hub_msgs/DockState").has_value());
  EXPECT_EQ(msg_text("hub_msgs/DockState"), msg_text("hub_msgs/msg/DockState"));
}

TEST(MsgDefinitions, MalformedOrUnknownNamesFindNothing) {
  for (const std::string_view name : {"", "DockState", "hub_msgs/", "/DockState", "hub_msgs/srv/DockState",
                                      "hub_msgs/msg/", "hub_msgs/msg/DockState/x", "hub_msgs/NoSuchType"}) {
    SCOPED_TRACE(std::string(name));
    EXPECT_FALSE(msg_text(name).has_value());
  }
  const Expected<std::string> schema = ros2msg_schema("hub_msgs/NoSuchType");
  ASSERT_FALSE(schema.is_ok());
  EXPECT_EQ(schema.error().code, ErrorCode::kNotFound);
  EXPECT_NE(schema.error().message.find("hub_msgs/NoSuchType"), std::string::npos) << schema.error().message;
}

}  // namespace
}  // namespace hubrt::msgs
