// The real hubd on the fake backend with the hub's test board (boards/host-sim-mir-com.yaml: the MiR100
// simulator's REST server on loopback, reached through the real cpp-httplib client), commanded
// over Cyclone DDS on loopback in the test's own domain (TestDomain) like a planner: the platform
// paused before any command, a move through the mission queue, the watchdog pausing a move and
// the same command letting it go on, REST faults from /sim/fault as clear errors while the
// heartbeat goes on, a clean stop.
#include <cmath>
#include <csignal>
#include <functional>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hubrt/runtime/lifecycle.h"
#include "hubrt/test_support/hub_under_test.h"

#include "mir_com_messages.h"

namespace hubrt::mir_com {
namespace {

using std::chrono::seconds;
using test_support::HubUnderTest;
using test_support::StateStream;
using View = hub_msgs::RobotMoverStateView;

// Generous: a busy 2-core machine running sanitizer builds in parallel; the test checks
// behaviour, not timing (a move of 2 m at the simulator's 1 m/s takes about 2 s).
constexpr auto kPatience = seconds(30);

std::string errors_of(const View& state) {
  std::string out;
  for (std::string_view error : state.error_list()) out += std::string(error) + "; ";
  return out;
}

class HubdMirComTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(commands_, "/robot_mover/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/mir_com/mover/state"));
    ASSERT_NO_FATAL_FAILURE(hub_.start(
        {.board = std::string(HUBRT_MIR_COM_DIR) + "/../../boards/host-sim-mir-com.yaml", .hub = "mir_com"}));
  }

  ::testing::AssertionResult wait_for(const std::function<bool(const View&)>& predicate,
                                      std::string_view what) {
    return hub_.wait_for(
        *states_, [&](const RobotMoverState& s) { return predicate(View(s)); }, what);
  }
  View last() const { return View(states_->latest()); }

  // Like the planner: the wanted command, repeated every 50 ms (the timeout is 1 s).
  void command(std::string_view action, std::string_view pose = "") {
    hub_msgs::RobotMoverCommand c;
    c.set_action(action);
    c.set_pose_name(pose);
    c.set_target_type("robot_mover");
    c.set_target_name("mover");
    c.set_robot_type("MIR100");
    c.set_robot_name("mir100");
    c.set_pose_type("POSITION");
    c.set_speed_scal(1.0F);
    c.set_acc_scal(1.0F);
    hub_.plan(*commands_, c.wire());
  }

  void sim_fault(const std::string& fault) { hub_.sim_fault("mir_com", "mir", fault); }

  dds::Writer<RobotMoverCommand>* commands_ = nullptr;
  StateStream<RobotMoverState>* states_ = nullptr;
  HubUnderTest hub_{kPatience};
};

TEST_F(HubdMirComTest, MovesThePlatformAndPausesItWhenThePlannerStops) {
  // No command yet: the hub holds the platform paused.
  ASSERT_TRUE(wait_for([](const View& s) { return s.answering() && s.platform_state() == "Pause"; },
                       "answering, paused"));
  EXPECT_TRUE(last().safe_hold());
  EXPECT_EQ(last().robot_name(), "mir100");

  command("move", "kit_pickup");
  ASSERT_TRUE(wait_for([](const View& s) { return s.moving() && s.fresh_msg(); }, "moving, fresh"));
  // Arrived (the status after the mission's Done shows where it stands).
  ASSERT_TRUE(wait_for(
      [](const View& s) { return s.actual_pose() == "kit_pickup" && std::abs(s.x() - 2.0F) < 1e-3F; },
      "at kit_pickup, x = 2"))
      << errors_of(last());
  EXPECT_EQ(last().done_action(), "moved");

  // A move to the station, and the planner goes quiet in the middle of it.
  command("move", "station");
  ASSERT_TRUE(wait_for([](const View& s) { return s.moving() && s.y() > 0.1F; }, "moving, y > 0.1"));
  hub_.stop_planner();
  ASSERT_TRUE(
      wait_for([](const View& s) { return !s.fresh_msg() && s.safe_hold() && s.platform_state() == "Pause"; },
               "not fresh, held paused"));
  EXPECT_FALSE(last().moving());
  EXPECT_NE(errors_of(last()).find("command timeout"), std::string::npos) << errors_of(last());
  const float y = last().y();
  EXPECT_FALSE(
      states_->take_until([](const RobotMoverState&) { return false; }, seconds(1)));  // a second of States
  EXPECT_EQ(last().y(), y) << "paused: it does not move";

  // The same command again: it goes on and gets there.
  command("move", "station");
  ASSERT_TRUE(
      wait_for([](const View& s) { return s.actual_pose() == "station" && std::abs(s.y() - 1.5F) < 1e-3F; },
               "at station, y = 1.5"))
      << errors_of(last());
}

TEST_F(HubdMirComTest, RestFaultsAreClearErrorsWhileTheHeartbeatGoesOn) {
  command("pause");
  ASSERT_TRUE(wait_for([](const View& s) { return s.answering() && s.done_action() == "paused"; },
                       "answering, paused by command"));
  for (const std::string_view fault :
       {"server_error", "unauthorized", "malformed_json", "stop_answering", "go_down"}) {
    SCOPED_TRACE(fault);
    ASSERT_NO_FATAL_FAILURE(sim_fault(std::string(fault)));
    const std::string expected = std::string(fault) == "server_error"     ? "HTTP 500"
                                 : std::string(fault) == "unauthorized"   ? "HTTP 401"
                                 : std::string(fault) == "malformed_json" ? "malformed JSON"
                                 : std::string(fault) == "stop_answering"
                                     ? "timeout:"
                                     : "cannot connect (refused or unreachable)";
    ASSERT_TRUE(wait_for([&](const View& s) { return errors_of(s).find(expected) != std::string::npos; },
                         "'" + expected + "' in error_list"))
        << errors_of(last());
    // Not answering for answer_within_ms: not operational (recovering), held paused; States go on.
    ASSERT_TRUE(wait_for(
        [](const View& s) {
          return !s.answering() &&
                 s.header().lifecycle() == static_cast<std::uint8_t>(runtime::Lifecycle::kRecovering) &&
                 s.safe_hold();
        },
        "not answering, recovering, held"))
        << errors_of(last());
    ASSERT_NO_FATAL_FAILURE(sim_fault(std::string(fault) == "go_down" ? "come_back" : "answer"));
    ASSERT_TRUE(wait_for(
        [](const View& s) {
          return s.answering() && s.error_list().size() == 0 &&
                 s.header().lifecycle() == static_cast<std::uint8_t>(runtime::Lifecycle::kOperational);
        },
        "answering again, no errors, operational"))
        << errors_of(last());
  }

  ASSERT_TRUE(hub_.hub().process().signal(SIGTERM));
  auto status = hub_.hub().process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hub_.output();
}

}  // namespace
}  // namespace hubrt::mir_com
