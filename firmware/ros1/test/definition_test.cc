// ROS 1 definitions and md5sums against what genmsg generated into roscpp's std_msgs headers
// (ros::message_traits: the definition and md5sum a roscpp publisher announces), and the hub's
// own definitions derived from the hub types' .msg texts (those built into the program, and a
// ROS 2 interface tree on disk).
#include "hubrt/ros1/definition.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>
#include <std_msgs/ColorRGBA.h>
#include <std_msgs/Header.h>
#include <std_msgs/MultiArrayLayout.h>
#include <std_msgs/String.h>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/definitions.h"

namespace hubrt::ros1 {
namespace {

template <class M>
void expect_md5_as_genmsg() {
  namespace traits = ros::message_traits;
  const std::string name = traits::DataType<M>::value();
  auto parsed = parse_full_definition(traits::Definition<M>::value(), name);
  ASSERT_TRUE(parsed) << parsed.error().message;
  auto md5 = md5sum(*parsed, name);
  ASSERT_TRUE(md5) << md5.error().message;
  EXPECT_EQ(*md5, traits::MD5Sum<M>::value()) << name;
  // Our own full definition of the parsed messages says the same.
  auto text = full_definition(*parsed, name);
  ASSERT_TRUE(text);
  auto again = parse_full_definition(*text, name);
  ASSERT_TRUE(again);
  EXPECT_EQ(*md5sum(*again, name), traits::MD5Sum<M>::value()) << *text;
}

TEST(Ros1Definition, Md5sumsAreGenmsgs) {
  expect_md5_as_genmsg<std_msgs::Header>();            // time, uint32, string
  expect_md5_as_genmsg<std_msgs::String>();            // one string
  expect_md5_as_genmsg<std_msgs::ColorRGBA>();         // float32 fields
  expect_md5_as_genmsg<std_msgs::MultiArrayLayout>();  // nested message array, comments
}

Messages hub_messages() {
  auto messages = load_definitions_as_ros1(msgs::msg_definitions());
  EXPECT_TRUE(messages) << messages.error().message;
  return messages ? *messages : Messages{};
}

// hub_msgs only: the standard ROS 2 types have ROS 1 forms of their own (time, std_msgs).
TEST(Ros1Definition, TheBuiltInDefinitionsGiveTheHubTypesOnly) {
  const Messages messages = hub_messages();
  EXPECT_TRUE(messages.contains("hub_msgs/DockState"));
  EXPECT_TRUE(messages.contains("hub_msgs/SimSignals"));
  EXPECT_FALSE(messages.contains("std_msgs/Header"));
  EXPECT_FALSE(messages.contains("builtin_interfaces/Time"));
}

// A tree on disk (hubbridge --msg-dir) reads as the same definitions.
TEST(Ros1Definition, AnInterfaceTreeOnDiskReadsLikeTheBuiltInTexts) {
  const auto root = std::filesystem::path(::testing::TempDir()) / "ros1_definition_tree";
  std::filesystem::create_directories(root / "hub_msgs" / "msg");
  for (const char* type : {"DockCommand", "DockSlot"}) {
    std::ofstream(root / "hub_msgs" / "msg" / (std::string(type) + ".msg"))
        << *msgs::msg_text(std::string("hub_msgs/") + type);
  }
  auto tree = load_ros2_tree_as_ros1(root);
  ASSERT_TRUE(tree) << tree.error().message;
  ASSERT_EQ(tree->size(), 2U);
  const Messages built_in = hub_messages();
  EXPECT_EQ(msg_text(tree->at("hub_msgs/DockCommand")), msg_text(built_in.at("hub_msgs/DockCommand")));
  EXPECT_FALSE(load_ros2_tree_as_ros1(root / "missing"));
}

TEST(Ros1Definition, Ros2MsgBecomesRos1Form) {
  const Messages messages = hub_messages();
  const Message& command = messages.at("hub_msgs/DockCommand");
  EXPECT_EQ(msg_text(command),
            "string ACTION_MONITOR=monitor\nstring ACTION_RESET=reset\n"
            "string target_type\nstring target_name\nstring action\n");
  const Message& header = messages.at("hub_msgs/StateHeader");
  ASSERT_EQ(header.fields.size(), 3U);
  EXPECT_EQ(header.fields[0].text(), "time stamp");
  const Message& state = messages.at("hub_msgs/DockState");
  EXPECT_EQ(state.fields.back().text(), "hub_msgs/DockSlot[] slots");
  EXPECT_EQ(state.fields[6].text(), "string[] error_list");
}

TEST(Ros1Definition, EveryHubTypeMatchesItsReflection) {
  const Messages messages = hub_messages();
  int checked = 0;
  for (const msgs::TypeInfo* type : msgs::all_types().types()) {
    if (!type->ros_name.starts_with("hub_msgs/")) continue;
    const auto ok = check_matches(messages, ros1_name_of(*type), *type);
    EXPECT_TRUE(ok) << ok.error().message;
    ++checked;
  }
  EXPECT_GT(checked, 20);
}

TEST(Ros1Definition, ReflectionMismatchNamesTheField) {
  Messages messages = hub_messages();
  messages.at("hub_msgs/DockSlot").fields[1].type = "uint8";  // occupied: bool in the IDL
  const auto* type = msgs::all_types().find("hub_msgs/msg/DockState");
  const auto ok = check_matches(messages, "hub_msgs/DockState", *type);
  ASSERT_FALSE(ok);
  EXPECT_NE(ok.error().message.find("hub_msgs/DockState.slots.occupied"), std::string::npos)
      << ok.error().message;
}

TEST(Ros1Definition, AnnouncedDefinitionDifferenceNamesTheField) {
  const Messages expected = hub_messages();
  auto text = full_definition(expected, "hub_msgs/DockState");
  ASSERT_TRUE(text);
  EXPECT_EQ(
      first_difference(expected, *parse_full_definition(*text, "hub_msgs/DockState"), "hub_msgs/DockState"),
      "");

  // A ROS 1 team's copy whose slot lost a field, with comments the way people write them.
  std::string changed = *text;
  changed.replace(changed.find("bool occupied"), 13, "# occupancy\nbool present  # renamed");
  auto announced = parse_full_definition(changed, "hub_msgs/DockState");
  ASSERT_TRUE(announced) << announced.error().message;
  const std::string diff = first_difference(expected, *announced, "hub_msgs/DockState");
  EXPECT_NE(diff.find("hub_msgs/DockState.slots.occupied"), std::string::npos) << diff;
  EXPECT_NE(diff.find("bool present"), std::string::npos) << diff;
  EXPECT_NE(*md5sum(*announced, "hub_msgs/DockState"), *md5sum(expected, "hub_msgs/DockState"));

  std::string constant = *text;
  constant.replace(constant.find("=monitor"), 8, "=watch");
  const std::string cdiff = first_difference(expected, *parse_full_definition(constant, "hub_msgs/DockState"),
                                             "hub_msgs/DockState");
  EXPECT_NE(cdiff.find("hub_msgs/DockState.echo: constant ACTION_MONITOR"), std::string::npos) << cdiff;
}

TEST(Ros1Definition, MalformedDefinitionsAreErrors) {
  EXPECT_FALSE(parse_ros1_msg("uint8", "p/T"));
  EXPECT_FALSE(parse_ros1_msg("uint8[x] a", "p/T"));
  EXPECT_FALSE(parse_ros1_msg("not-a-type a", "p/T"));
  EXPECT_FALSE(parse_full_definition("uint8 a\n" + std::string(80, '=') + "\nNOPE\n", "p/T"));
  Messages incomplete;
  incomplete["p/T"] = *parse_ros1_msg("p/U u", "p/T");
  EXPECT_FALSE(md5sum(incomplete, "p/T"));
  EXPECT_FALSE(full_definition(incomplete, "p/T"));
}

// A ROS 1 peer announces the definitions: one whose type contains itself (found by the fuzzer as
// a stack overflow in md5sum) is an error, directly or through another type.
TEST(Ros1Definition, ADefinitionThatContainsItselfIsAnError) {
  Messages direct;
  direct["p/T"] = *parse_ros1_msg("uint8 a\np/T inner", "p/T");
  auto sum = md5sum(direct, "p/T");
  ASSERT_FALSE(sum);
  EXPECT_NE(sum.error().message.find("p/T: the message definition contains itself"), std::string::npos)
      << sum.error().message;
  Messages through;
  through["p/T"] = *parse_ros1_msg("p/U[] us", "p/T");
  through["p/U"] = *parse_ros1_msg("string s\np/T back", "p/U");
  EXPECT_FALSE(md5sum(through, "p/T"));
  EXPECT_TRUE(full_definition(through, "p/T"));  // each type once, and it ends
  // A type used twice is no cycle.
  Messages shared;
  shared["p/T"] = *parse_ros1_msg("p/U first\np/U second", "p/T");
  shared["p/U"] = *parse_ros1_msg("int32 x", "p/U");
  EXPECT_TRUE(md5sum(shared, "p/T"));
}

}  // namespace
}  // namespace hubrt::ros1
