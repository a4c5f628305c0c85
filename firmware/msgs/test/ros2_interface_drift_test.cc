// The drift test: the ROS 2 interface package (ros2/*/msg/*.msg) and the standard ROS 2 layouts
// we mirror (test/ros2_reference/) must describe exactly the types idlc generated from our IDL —
// every type of every message target, hubs/* included, through all_types().
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"
#include "hubrt/msgs/drift.h"
#include "hubrt/msgs/ros_msg.h"

namespace hubrt::msgs {
namespace {

TEST(Ros2InterfaceDrift, MsgFilesMatchTheIdlOfEveryMessageTarget) {
  auto ours = ros::load_msg_packages(HUBRT_ROS2_DIR);
  ASSERT_TRUE(ours) << ours.error().message;
  auto reference = ros::load_msg_packages(HUBRT_ROS2_REFERENCE_DIR);
  ASSERT_TRUE(reference) << reference.error().message;
  std::vector<ros::MsgSpec> msgs = std::move(*ours);
  msgs.insert(msgs.end(), reference->begin(), reference->end());

  // Guard against a vacuous pass: the hub package and the registry must really be there.
  ASSERT_TRUE(std::any_of(msgs.begin(), msgs.end(),
                          [](const auto& m) { return m.ros_name() == "hub_msgs/msg/DockState"; }))
      << "ros2/hub_msgs/msg/DockState.msg not found under " << HUBRT_ROS2_DIR;
  ASSERT_NE(all_types().find("hub_msgs/msg/DockState"), nullptr);

  const auto drift = find_drift(msgs, all_types().types());
  std::string report;
  for (const auto& sentence : drift) report += "  - " + sentence + "\n";
  EXPECT_TRUE(drift.empty()) << "the .msg files and the IDL differ (fix one side):\n" << report;
}

}  // namespace
}  // namespace hubrt::msgs
