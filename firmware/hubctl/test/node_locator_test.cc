// Finding a node's command and State topics from discovery, under both layouts.
#include "node_locator.h"

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/msgs/all_types.h"

namespace hubrt::hubctl {
namespace {

using ::testing::HasSubstr;

dds::Guid guid(std::uint8_t n) {
  dds::Guid g;
  g.bytes[0] = n;
  return g;
}

class NodeLocatorTest : public ::testing::Test {
 protected:
  void participant(std::uint8_t id, std::string name) {
    snapshot_.participants.push_back(dds::DiscoveredParticipant{guid(id), std::move(name), false});
  }
  void endpoint(std::uint8_t owner, dds::EndpointDirection direction, std::string topic, std::string type) {
    dds::DiscoveredEndpoint e;
    e.direction = direction;
    e.topic_name = std::move(topic);
    e.type_name = std::move(type);
    e.participant_key = guid(owner);
    snapshot_.endpoints.push_back(std::move(e));
  }
  std::optional<NodeEndpoints> locate(std::string_view hub, std::string_view node,
                                      std::string_view ros_namespace = {}) {
    return locate_node(snapshot_, msgs::all_types(), hub, node, why_, ros_namespace);
  }

  dds::DiscoverySnapshot snapshot_;
  std::string why_;
};

constexpr auto kWriter = dds::EndpointDirection::kWriter;
constexpr auto kReader = dds::EndpointDirection::kReader;

TEST_F(NodeLocatorTest, NodeTypeLayout) {
  participant(1, "dock_ecu");
  endpoint(1, kWriter, "rt/dock_ecu/dock/state", "hub_msgs::msg::dds_::DockState_");
  endpoint(1, kReader, "rt/dock/command", "hub_msgs::msg::dds_::DockCommand_");
  endpoint(1, kReader, "rt/sim/input", "hub_msgs::msg::dds_::SimInput_");
  auto found = locate("dock_ecu", "dock");
  ASSERT_TRUE(found) << why_;
  EXPECT_EQ(found->layout, Layout::kNodeType);
  EXPECT_EQ(found->command_topic, "/dock/command");
  EXPECT_EQ(found->state_topic, "/dock_ecu/dock/state");
  EXPECT_EQ(found->target_type, "dock");
  EXPECT_EQ(found->field, "");
  EXPECT_EQ(found->command_type->ros_name, "hub_msgs/msg/DockCommand");
  EXPECT_EQ(found->node_command_type, found->command_type);
}

TEST_F(NodeLocatorTest, HubLayoutWithANamespace) {
  participant(1, "dock2");
  endpoint(1, kWriter, "rt/station1/dock2/state", "hub_msgs::msg::dds_::DockEcuState_");
  endpoint(1, kReader, "rt/station1/dock2/command", "hub_msgs::msg::dds_::DockEcuCommand_");
  auto found = locate("dock2", "dock");
  ASSERT_TRUE(found) << why_;
  EXPECT_EQ(found->layout, Layout::kHub);
  EXPECT_EQ(found->command_topic, "/station1/dock2/command");
  EXPECT_EQ(found->state_topic, "/station1/dock2/state");
  EXPECT_EQ(found->field, "dock");
  EXPECT_EQ(found->target_type, "dock_ecu") << "the hub type, from the hub command's type name";
  EXPECT_EQ(found->node_command_type->ros_name, "hub_msgs/msg/DockCommand");
}

// Stations sharing one domain (docs/plant.md): a Dock ECU in each, all named dock_ecu, each under
// its station's namespace; the namespace picks one, and none is found under a namespace no station has.
TEST_F(NodeLocatorTest, TheNamespacePicksOneOfSeveralStationsHubsOfTheSameName) {
  for (std::uint8_t k = 1; k <= 3; ++k) {
    participant(k, "dock_ecu");
    endpoint(k, kWriter, fmt::format("rt/cell{}/dock_ecu/dock/state", k), "hub_msgs::msg::dds_::DockState_");
    endpoint(k, kReader, fmt::format("rt/cell{}/dock/command", k), "hub_msgs::msg::dds_::DockCommand_");
  }
  auto found = locate("dock_ecu", "dock", "/cell2");
  ASSERT_TRUE(found) << why_;
  EXPECT_EQ(found->state_topic, "/cell2/dock_ecu/dock/state");
  EXPECT_EQ(found->command_topic, "/cell2/dock/command");
  // A namespace is a whole name: /cell is no prefix of /cell2's topics.
  EXPECT_FALSE(locate("dock_ecu", "dock", "/cell"));
  EXPECT_FALSE(locate("dock_ecu", "dock", "/cell4"));
  EXPECT_THAT(why_, HasSubstr("publishes no State of a node 'dock'"));
}

TEST_F(NodeLocatorTest, AnotherHubsEndpointsDoNotCount) {
  participant(1, "dock_ecu");
  participant(2, "other");
  endpoint(2, kWriter, "rt/dock_ecu/dock/state", "hub_msgs::msg::dds_::DockState_");
  endpoint(2, kReader, "rt/dock/command", "hub_msgs::msg::dds_::DockCommand_");
  EXPECT_FALSE(locate("dock_ecu", "dock"));
  EXPECT_THAT(why_, HasSubstr("hub 'dock_ecu' publishes no State of a node 'dock'"));
}

TEST_F(NodeLocatorTest, SaysWhatIsThereWhenTheNodeIsNot) {
  EXPECT_FALSE(locate("dock_ecu", "dock"));
  EXPECT_THAT(why_, HasSubstr("no hub 'dock_ecu' on the domain (participants seen: none)"));
  participant(1, "dock_ecu");
  endpoint(1, kWriter, "rt/dock_ecu/dock/state", "hub_msgs::msg::dds_::DockState_");
  endpoint(1, kReader, "rt/dock/command", "hub_msgs::msg::dds_::DockCommand_");
  EXPECT_FALSE(locate("dock_ecu", "dok"));
  EXPECT_THAT(why_, HasSubstr("it publishes: /dock_ecu/dock/state"));
  participant(2, "dock_hub");
  endpoint(2, kWriter, "rt/dock_hub/state", "hub_msgs::msg::dds_::DockEcuState_");
  endpoint(2, kReader, "rt/dock_hub/command", "hub_msgs::msg::dds_::DockEcuCommand_");
  EXPECT_FALSE(locate("dock_hub", "dok"));
  EXPECT_THAT(why_,
              HasSubstr("runs the hub layout (/dock_hub/state) and has no node 'dok' (its nodes: dock)"));
}

TEST(SnakeCase, FromTypeStem) {
  EXPECT_EQ(snake_case("ToolEcu"), "tool_ecu");
  EXPECT_EQ(snake_case("DockEcu"), "dock_ecu");
  EXPECT_EQ(snake_case("Rsp"), "rsp");
}

}  // namespace
}  // namespace hubrt::hubctl
