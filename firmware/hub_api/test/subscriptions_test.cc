#include "hubrt/hub_api/subscriptions.h"

#include <thread>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/test_domain.h"

#include "dock_messages.h"

namespace hubrt::hub_api {
namespace {

using dock_ecu::DockState;
using std::chrono::milliseconds;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::StartsWith;

config::HubConfig config_with(const std::string& subscriptions_yaml) {
  auto root = config::YamlMap::load_string(
      "hub: tool_ecu\nnodes:\n  tool: {type: smart_tool}\nsubscriptions:\n" + subscriptions_yaml,
      "tool.yaml");
  EXPECT_TRUE(root) << root.error().message;
  auto config = config::parse_hub_config(*root);
  EXPECT_TRUE(config) << config.error().message;
  return *config;
}

class SubscriptionsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "subscriber");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  ManualClock clock_;
};

TEST_F(SubscriptionsTest, AFreshStateIsHandedToTheLogicAndALostOneIsNot) {
  const auto config =
      config_with("  dock: {topic: /dock_ecu/dock/state, type: hub_msgs/msg/DockState, timeout_ms: 300}\n");
  Subscriptions subscriptions(config, *participant_);
  auto dock = subscriptions.get<DockState>("dock");
  ASSERT_TRUE(dock) << dock.error().message;
  auto stage = subscriptions.make_stage();
  ASSERT_NE(stage, nullptr);
  EXPECT_EQ((*dock)->fresh(clock_.now().mono), nullptr);
  EXPECT_EQ((*dock)->loss_reason(clock_.now().mono),
            "input 'dock' (/dock_ecu/dock/state): no State received yet");

  auto topic = dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state");
  ASSERT_TRUE(topic);
  auto writer = dds::Writer<DockState>::create(*participant_, *topic);
  ASSERT_TRUE(writer);
  hub_msgs_msg_dds__DockSlot_ slot{"smart_tool", true};
  DockState state{};
  hubrt::msgs::typed::assign(state.name, "dock");
  state.slots._buffer = &slot;
  state.slots._length = 1;
  state.slots._maximum = 1;
  ASSERT_TRUE(writer->write(state).is_ok());
  // Delivery within one process is quick, but not synchronous: poll with a deadline.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(10);
  while (!(*dock)->ever_received() && std::chrono::steady_clock::now() < deadline) {
    stage->before_nodes(clock_.now());
    std::this_thread::sleep_for(milliseconds(1));
  }
  const DockState* seen = (*dock)->fresh(clock_.now().mono);
  ASSERT_NE(seen, nullptr);
  ASSERT_EQ(seen->slots._length, 1u);
  EXPECT_STREQ(seen->slots._buffer[0].name, "smart_tool");
  EXPECT_TRUE(seen->slots._buffer[0].occupied);
  EXPECT_TRUE((*dock)->loss_reason(clock_.now().mono).empty());

  clock_.advance(milliseconds(301));
  EXPECT_EQ((*dock)->fresh(clock_.now().mono), nullptr) << "older than the timeout counts as lost";
  EXPECT_EQ((*dock)->loss_reason(clock_.now().mono),
            "input 'dock' (/dock_ecu/dock/state): no State for 0.30 s (limit 0.30 s)");
}

TEST_F(SubscriptionsTest, WrongOrMissingConfigurationIsRefusedWithTheFile) {
  const auto config = config_with(
      "  dock: {topic: /dock_ecu/dock/state, type: hub_msgs/msg/DockCommand}\n"
      "  other: {topic: /x/state, type: hub_msgs/msg/Nothing}\n"
      "  hub: {topic: /x/state, type: hub_msgs/msg/DockState, field: dock}\n"
      "  typo: {topic: /x/state, type: hub_msgs/msg/DockStat}\n");
  Subscriptions subscriptions(config, *participant_);
  EXPECT_EQ(subscriptions.get<DockState>("dock").error().message,
            "tool.yaml: subscriptions.dock: input 'dock' must be a hub_msgs/msg/DockState, not "
            "hub_msgs/msg/DockCommand");
  // Which types a program knows depends on what it links (a board program: its hub type's), so
  // the message says so; a near miss is named.
  EXPECT_THAT(
      subscriptions.get<DockState>("other").error().message,
      AllOf(StartsWith("tool.yaml: subscriptions.other.type: unknown message type 'hub_msgs/msg/Nothing'"),
            HasSubstr("(this hubd holds the message types of its hub types and their inputs)")));
  EXPECT_THAT(subscriptions.get<DockState>("typo").error().message,
              HasSubstr("unknown message type 'hub_msgs/msg/DockStat'; did you mean hub_msgs/msg/DockState"));
  EXPECT_EQ(subscriptions.get<DockState>("hub").error().message,
            "tool.yaml: subscriptions.hub.field: hub_msgs/msg/DockState has no field 'dock' of type "
            "hub_msgs/msg/DockState");
  EXPECT_NE(subscriptions.get<DockState>("rsp").error().message.find("add it under subscriptions:"),
            std::string::npos);
  EXPECT_EQ(subscriptions.make_stage(), nullptr);
}

}  // namespace
}  // namespace hubrt::hub_api
