#include "hubrt/dds/ros_names.h"

#include <gtest/gtest.h>

namespace hubrt::dds {
namespace {

std::string message_for_topic(std::string_view name) {
  auto result = validate_ros_topic_name(name);
  return result ? std::string("<valid>") : result.error().message;
}

TEST(RosNames, TopicGetsTheRtPrefix) {
  auto dds_name = ros_to_dds_topic("/dock/command");
  ASSERT_TRUE(dds_name) << dds_name.error().message;
  EXPECT_EQ(*dds_name, "rt/dock/command");
  EXPECT_EQ(*ros_to_dds_topic("/diagnostics"), "rt/diagnostics");
  EXPECT_EQ(*ros_to_dds_topic("/tool_ecu/Tool_1/state"), "rt/tool_ecu/Tool_1/state");
}

TEST(RosNames, InvalidTopicNamesSayWhichRuleTheyBreak) {
  EXPECT_NE(message_for_topic("").find("is empty"), std::string::npos);
  EXPECT_NE(message_for_topic("dock/command").find("must start with '/'"), std::string::npos);
  EXPECT_NE(message_for_topic("/").find("names no topic"), std::string::npos);
  EXPECT_NE(message_for_topic("/dock/").find("must not end with '/'"), std::string::npos);
  EXPECT_NE(message_for_topic("/dock//command").find("'//'"), std::string::npos);
  EXPECT_NE(message_for_topic("/dock/1command").find("starting with a digit"), std::string::npos);
  const std::string bad_char = message_for_topic("/dock-1/command");
  EXPECT_NE(bad_char.find("'-' at offset 5"), std::string::npos) << bad_char;
  EXPECT_NE(bad_char.find("'/dock-1/command'"), std::string::npos) << bad_char;
  EXPECT_NE(message_for_topic("/dock command").find("' '"), std::string::npos);
  EXPECT_NE(message_for_topic("/~/private").find("'~'"), std::string::npos);
  EXPECT_EQ(ros_to_dds_topic("dock").error().code, ErrorCode::kInvalidArgument);
}

TEST(RosNames, DdsTopicBackToRos) {
  EXPECT_EQ(dds_to_ros_topic("rt/dock/command"), "/dock/command");
  EXPECT_EQ(dds_to_ros_topic("rq/add_two_intsRequest"), std::nullopt);
  EXPECT_EQ(dds_to_ros_topic("DCPSParticipant"), std::nullopt);
  EXPECT_EQ(dds_to_ros_topic("rt/"), std::nullopt);
  EXPECT_EQ(dds_to_ros_topic("rtx/a"), std::nullopt);
}

TEST(RosNames, TypeNamesBothWays) {
  auto ros = dds_to_ros_type("hub_msgs::msg::dds_::DockCommand_");
  ASSERT_TRUE(ros) << ros.error().message;
  EXPECT_EQ(*ros, "hub_msgs/msg/DockCommand");
  auto dds = ros_to_dds_type("hub_msgs/msg/DockCommand");
  ASSERT_TRUE(dds) << dds.error().message;
  EXPECT_EQ(*dds, "hub_msgs::msg::dds_::DockCommand_");
  EXPECT_EQ(*dds_to_ros_type("diagnostic_msgs::msg::dds_::DiagnosticArray_"),
            "diagnostic_msgs/msg/DiagnosticArray");
  EXPECT_EQ(*ros_to_dds_type(*dds_to_ros_type("std_srvs::srv::dds_::Trigger_Request_")),
            "std_srvs::srv::dds_::Trigger_Request_");
}

TEST(RosNames, NonRosTypeNamesAreRejected) {
  for (const char* name : {"hub_msgs::msg::DockCommand_", "hub_msgs::msg::dds_::DockCommand", "DockCommand_",
                           "hub_msgs::foo::dds_::DockCommand_", "a::b::msg::dds_::T_", "::msg::dds_::T_"}) {
    auto result = dds_to_ros_type(name);
    ASSERT_FALSE(result) << name;
    EXPECT_EQ(result.error().code, ErrorCode::kInvalidArgument);
    EXPECT_NE(result.error().message.find(name), std::string::npos) << result.error().message;
  }
  for (const char* name : {"hub_msgs/DockCommand", "hub_msgs/msg/Dock/Command", "hub_msgs/msgs/DockCommand",
                           "/msg/DockCommand", "hub msgs/msg/DockCommand"}) {
    EXPECT_FALSE(ros_to_dds_type(name)) << name;
  }
}

}  // namespace
}  // namespace hubrt::dds
