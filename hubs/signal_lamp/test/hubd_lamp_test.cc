// The real hubd on the fake backend with the hub's own test board (test/lamp-sim.yaml), commanded
// over Cyclone DDS on loopback in the test's own domain (TestDomain): what the runtime gives a new
// hub type for free (echo, fresh_msg, the watchdog, the lifecycle, a clean stop) around the lamp.
#include <csignal>
#include <functional>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hubrt/runtime/lifecycle.h"
#include "hubrt/test_support/hub_under_test.h"

#include "lamp_messages.h"

namespace hubrt::signal_lamp {
namespace {

using test_support::HubUnderTest;
using test_support::StateStream;

hub_msgs::LampStateView view(const LampState& state) {
  return hub_msgs::LampStateView(state);
}

std::string errors_of(const LampState& state) {
  std::string out;
  for (std::string_view error : view(state).error_list()) out += std::string(error) + "; ";
  return out;
}

bool operational(const LampState& state) {
  return view(state).header().lifecycle() == static_cast<std::uint8_t>(runtime::Lifecycle::kOperational);
}

hub_msgs::LampCommand lamp_command(std::string_view action) {
  hub_msgs::LampCommand c;
  c.set_target_type("lamp");
  c.set_target_name("lamp");
  c.set_action(action);
  return c;
}

class HubdLampTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    // The node-type layout's topics (signal_lamp.yaml): /lamp/command, /signal_lamp/lamp/state.
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(commands_, "/lamp/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/signal_lamp/lamp/state"));
    ASSERT_NO_FATAL_FAILURE(hub_.start(
        {.board = std::string(HUBRT_SIGNAL_LAMP_DIR) + "/test/lamp-sim.yaml", .hub = "signal_lamp"}));
  }

  // Takes States until one satisfies `predicate` (then state()).
  ::testing::AssertionResult wait_for(const std::function<bool(const LampState&)>& predicate,
                                      std::string_view what) {
    return hub_.wait_for(*states_, predicate, what);
  }
  const LampState& state() const { return states_->latest(); }

  // Like the planner: the wanted command, repeated every 50 ms (the timeout is 1 s).
  void command(std::string_view action) { hub_.plan(*commands_, lamp_command(action).wire()); }

  dds::Writer<LampCommand>* commands_ = nullptr;
  StateStream<LampState>* states_ = nullptr;
  HubUnderTest hub_;
};

TEST_F(HubdLampTest, FollowsItsCommandOverDdsAndGoesOutWhenCommandsStop) {
  // No command yet: out, not operational, not fresh.
  ASSERT_TRUE(wait_for([](const LampState&) { return true; }, "any State"));
  EXPECT_FALSE(view(state()).lit());
  EXPECT_FALSE(view(state()).fresh_msg());
  EXPECT_FALSE(operational(state()));
  EXPECT_EQ(view(state()).name(), "lamp");

  command("on");
  ASSERT_TRUE(wait_for(
      [](const LampState& s) {
        return view(s).lit() && view(s).fresh_msg() && view(s).echo().action() == "on" && operational(s);
      },
      "lit, fresh, operational, echoing 'on'"));
  EXPECT_EQ(view(state()).error_list().size(), 0u) << errors_of(state());

  command("off");
  ASSERT_TRUE(wait_for([](const LampState& s) { return !view(s).lit() && view(s).echo().action() == "off"; },
                       "out, echoing 'off'"));

  command("on");
  ASSERT_TRUE(wait_for([](const LampState& s) { return view(s).lit(); }, "lit"));
  // The planner goes quiet: after the 1 s command timeout the watchdog puts the lamp out.
  hub_.stop_planner();
  ASSERT_TRUE(wait_for([](const LampState& s) { return !view(s).fresh_msg(); }, "not fresh"));
  EXPECT_FALSE(view(state()).lit());
  EXPECT_FALSE(operational(state()));
  EXPECT_NE(errors_of(state()).find("command timeout"), std::string::npos) << errors_of(state());
  EXPECT_EQ(view(state()).echo().action(), "on") << "the echo still shows the last command";

  // A bad action is rejected with its reason, naming the lamp's actions.
  ASSERT_TRUE(commands_->write(lamp_command("blink").wire()).is_ok());
  ASSERT_TRUE(wait_for(
      [](const LampState& s) {
        return errors_of(s).find("unknown action 'blink' (expected one of: on, off, reset)") !=
               std::string::npos;
      },
      "the rejection of 'blink' in error_list"));

  EXPECT_TRUE(hub_.stops_cleanly(SIGTERM));
}

}  // namespace
}  // namespace hubrt::signal_lamp
