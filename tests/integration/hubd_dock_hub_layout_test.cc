// The Dock ECU in the hub-oriented layout: one command and one State topic for the hub; the
// distributor hands the node its fragment, the collector assembles the hub State.
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/hub_under_test.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockEcuTypes;
using HubCommand = DockEcuTypes::Command::Wire;
using HubState = DockEcuTypes::State::Wire;
using test_support::HubUnderTest;
using test_support::StateStream;

std::string errors_of(const hub_msgs_msg_dds__DockState_& s) {
  std::string out;
  for (std::uint32_t i = 0; i < s.error_list._length; ++i) out += std::string(s.error_list._buffer[i]) + "; ";
  return out;
}

class HubdDockHubLayoutTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(writer_, "/dock_ecu/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/dock_ecu/state"));
    // The shipped configuration with the hub layout.
    ASSERT_NO_FATAL_FAILURE(hub_.start({.hub = hub_.hub_file("dock_ecu", "hub")}));
  }

  ::testing::AssertionResult wait_for_state(const std::function<bool(const HubState&)>& predicate,
                                            std::string_view what) {
    return hub_.wait_for(*states_, predicate, what);
  }
  const HubState& state() const { return states_->latest(); }

  // A planner repeating one hub command until stopped.
  void start_planner(const char* fragment_name) {
    HubCommand command{};
    hubrt::msgs::typed::assign(command.target_type, "dock_ecu");
    hubrt::msgs::typed::assign(command.target_name, "dock_ecu");
    hubrt::msgs::typed::assign(command.action, "apply");
    hubrt::msgs::typed::assign(command.dock.target_type, "");
    hubrt::msgs::typed::assign(command.dock.target_name, fragment_name);
    hubrt::msgs::typed::assign(command.dock.action, "monitor");
    hub_.plan([this, command] { writer_->write(command).ignore(); });
  }

  dds::Writer<HubCommand>* writer_ = nullptr;
  StateStream<HubState>* states_ = nullptr;
  HubUnderTest hub_;
};

TEST_F(HubdDockHubLayoutTest, TheHubCommandReachesTheNodeAndTheHubStateCarriesIt) {
  start_planner("");
  ASSERT_TRUE(wait_for_state(
      [](const HubState& s) {
        return s.fresh_msg && std::string(s.echo.action) == "apply" && s.dock.fresh_msg &&
               std::string(s.dock.echo.action) == "monitor" && std::string(s.dock.echo.target_name) == "dock";
      },
      "hub and node fresh, the node echoing 'monitor' to 'dock'"));
  EXPECT_STREQ(state().name, "dock_ecu");
  EXPECT_STREQ(state().dock.name, "dock");
  EXPECT_STREQ(state().dock.echo.target_type, "dock") << "an empty fragment target means this node";
  EXPECT_EQ(state().dock.slots._length, 4u);
  // The planner stops: the hub-level watchdog trips, then the node's (no more fragments).
  hub_.stop_planner();
  ASSERT_TRUE(wait_for_state([](const HubState& s) { return !s.fresh_msg && !s.dock.fresh_msg; },
                             "hub and node not fresh"));
  EXPECT_NE(errors_of(state().dock).find("command timeout"), std::string::npos) << errors_of(state().dock);
}

TEST_F(HubdDockHubLayoutTest, AFragmentForAnotherNodeIsRejectedByTheNode) {
  start_planner("dock9");
  const ::testing::AssertionResult rejected = wait_for_state(
      [](const HubState& s) {
        return s.fresh_msg &&
               errors_of(s.dock).find("wrong target: addressed to 'dock9', this node is 'dock'") !=
                   std::string::npos;
      },
      "the node rejecting the fragment for 'dock9'");
  hub_.stop_planner();
  ASSERT_TRUE(rejected);
  EXPECT_FALSE(state().dock.fresh_msg) << "nothing took effect in the node";
}

}  // namespace
}  // namespace hubrt::integration
