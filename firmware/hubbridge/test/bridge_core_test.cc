// What a bridge does to each ROS 1 message, without ROS 1 or DDS: the publisher check names the
// field that differs, bounds are enforced (dropped, never cut), stale samples are refused.
#include "bridge_core.h"

#include <cstring>

#include <gtest/gtest.h>

#include "hubrt/msgs/definitions.h"
#include "hubrt/ros1/codec.h"

#include "dock_reflect.h"
#include "dock_typed.h"

namespace hubrt::hubbridge {
namespace {

ros1::Messages hub_messages() {
  auto messages = ros1::load_definitions_as_ros1(msgs::msg_definitions());
  EXPECT_TRUE(messages) << messages.error().message;
  return messages ? *messages : ros1::Messages{};
}

std::vector<std::uint8_t> state_bytes(std::uint64_t seq, std::int32_t sec,
                                      const std::string& slot = "spare") {
  hub_msgs::DockState state;
  state.header().set_seq(seq);
  state.header().stamp().set_sec(sec);
  state.set_name("dock");
  state.slots().append()->set_name("smart_tool");
  std::vector<std::uint8_t> bytes;
  ros1::encode(msgs::type_info_of<hub_msgs_msg_dds__DockState_>(), &state.wire(), bytes);
  if (slot.size() > 64) {  // over the bound: rewrite the last slot's name by hand
    bytes.resize(bytes.size() - 4 - std::strlen("smart_tool") - 1);
    const auto n = static_cast<std::uint32_t>(slot.size());
    bytes.insert(bytes.end(), reinterpret_cast<const std::uint8_t*>(&n),
                 reinterpret_cast<const std::uint8_t*>(&n) + 4);
    bytes.insert(bytes.end(), slot.begin(), slot.end());
    bytes.push_back(0);
  }
  return bytes;
}

TEST(HubbridgeCore, BridgedTypeCarriesGenmsgForm) {
  const auto messages = hub_messages();
  auto type = bridged_type("hub_msgs/DockState", messages);
  ASSERT_TRUE(type) << type.error().message;
  EXPECT_EQ(type->ros1_name, "hub_msgs/DockState");
  EXPECT_EQ(type->md5sum.size(), 32U);
  EXPECT_NE(type->definition.find("MSG: hub_msgs/StateHeader"), std::string::npos);
  EXPECT_FALSE(bridged_type("hub_msgs/DockStat", messages));
}

TEST(HubbridgeCore, PublisherWithOtherDefinitionIsRefusedNamingTheField) {
  const auto messages = hub_messages();
  auto type = bridged_type("hub_msgs/DockState", messages);
  ASSERT_TRUE(type);
  Ros1Inbound inbound(*type, messages);
  EXPECT_EQ(inbound.check_publisher("/dock", type->ros1_name, type->md5sum, type->definition), "");

  std::string other = type->definition;
  other.replace(other.find("float32 t_plus"), 14, "float64 t_plus");
  const std::string problem = inbound.check_publisher("/old_dock", type->ros1_name, "0123", other);
  EXPECT_NE(problem.find("hub_msgs/DockState.t_plus"), std::string::npos) << problem;
  EXPECT_NE(problem.find("/old_dock"), std::string::npos) << problem;
  EXPECT_NE(inbound.check_publisher("/x", "std_msgs/String", type->md5sum, type->definition), "");
}

TEST(HubbridgeCore, KeepsRos1SeqAndStampAndRefusesStaleRepeats) {
  const auto messages = hub_messages();
  Ros1Inbound inbound(*bridged_type("hub_msgs/DockState", messages), messages);
  std::string why;
  ASSERT_EQ(inbound.take(state_bytes(7, 100), &why), Verdict::kForward) << why;
  const auto* sample = static_cast<const hub_msgs_msg_dds__DockState_*>(inbound.sample());
  EXPECT_EQ(sample->header.seq, 7U);  // the ROS 1 side's, not renumbered
  EXPECT_EQ(sample->header.stamp.sec, 100);
  // The same sample again (a latched publisher re-sending after a reconnect): not new.
  EXPECT_EQ(inbound.take(state_bytes(7, 100), &why), Verdict::kStale);
  EXPECT_EQ(inbound.take(state_bytes(6, 99), &why), Verdict::kStale);
  EXPECT_EQ(inbound.take(state_bytes(8, 101), &why), Verdict::kForward);
  // The ECU restarted: its seq starts again, its stamp is newer.
  EXPECT_EQ(inbound.take(state_bytes(0, 200), &why), Verdict::kForward);
}

TEST(HubbridgeCore, OverBoundIsDroppedNotCut) {
  const auto messages = hub_messages();
  Ros1Inbound inbound(*bridged_type("hub_msgs/DockState", messages), messages);
  std::string why;
  EXPECT_EQ(inbound.take(state_bytes(1, 1, std::string(65, 'x')), &why), Verdict::kOverBound);
  EXPECT_NE(why.find("slots[0].name"), std::string::npos) << why;
  EXPECT_EQ(inbound.take({}, &why), Verdict::kTypeError);
}

}  // namespace
}  // namespace hubrt::hubbridge
