// The bridge file: what it accepts and the errors that name file, line and key.
#include "bridge_config.h"

#include <gtest/gtest.h>

namespace hubrt::hubbridge {
namespace {

TEST(HubbridgeConfig, ReadsBridges) {
  auto file = load_bridge_text(R"(
name: dock_bridge
msg_dir: ../ros2
silent_after_ms: 500
bridges:
  - {ros1_topic: /dock_ecu/dock/state, dds_topic: /dock_ecu/dock/state, type: hub_msgs/DockState, direction: ros1_to_dds}
  - {ros1_topic: /dock/command, dds_topic: /dock/command, type: hub_msgs/DockCommand, direction: dds_to_ros1, qos: best_effort, depth: 1}
)",
                               "b.yaml", "/x/y");
  ASSERT_TRUE(file) << file.error().message;
  EXPECT_EQ(file->name, "dock_bridge");
  EXPECT_EQ(file->msg_dir, "/x/ros2");
  EXPECT_DOUBLE_EQ(file->silent_after_s, 0.5);
  ASSERT_EQ(file->bridges.size(), 2U);
  EXPECT_EQ(file->bridges[1].direction, Direction::kDdsToRos1);
  EXPECT_EQ(file->bridges[1].reliability, Reliability::kBestEffort);
  EXPECT_EQ(file->bridges[1].depth, 1);
}

// Without msg_dir the bridge takes the .msg texts built into it: the path stays empty.
TEST(HubbridgeConfig, MsgDirIsOptional) {
  auto file = load_bridge_text(
      "bridges:\n  - {ros1_topic: /a, dds_topic: /a, type: hub_msgs/DockState, direction: ros1_to_dds}\n",
      "b.yaml", "/x/y");
  ASSERT_TRUE(file) << file.error().message;
  EXPECT_EQ(file->msg_dir, "");
}

void expect_error(const std::string& text, const std::string& part) {
  auto file = load_bridge_text(text, "b.yaml", ".");
  ASSERT_FALSE(file) << text;
  EXPECT_NE(file.error().message.find(part), std::string::npos) << file.error().message;
}

TEST(HubbridgeConfig, RefusesWhatIsWrong) {
  const std::string head = "msg_dir: r\nbridges:\n";
  expect_error(head + "  - {ros1_topic: /a, dds_topic: /a, type: T, direction: both}\n", "direction");
  expect_error(head + "  - {ros1_topic: /a, dds_topic: /a, type: T, direction: ros1_to_dds, speed: 3}\n",
               "speed");
  expect_error(head + "  - {ros1_topic: 'a b', dds_topic: /a, type: T, direction: ros1_to_dds}\n", "b.yaml");
  expect_error(head +
                   "  - {ros1_topic: /a, dds_topic: /x, type: T, direction: ros1_to_dds}\n"
                   "  - {ros1_topic: /b, dds_topic: /x, type: T, direction: ros1_to_dds}\n",
               "a second bridge publishes dds /x");
  expect_error(head + "  - {ros1_topic: /a, dds_topic: /x, type: T, direction: ros1_to_dds, latch: true}\n",
               "latch");
  expect_error("msg_dir: r\nbridges: []\n", "no bridges");
}

}  // namespace
}  // namespace hubrt::hubbridge
