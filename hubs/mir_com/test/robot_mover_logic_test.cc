// The robot mover under a manual clock against the simulated platform: paused (once) while not
// operational, moving through the mission queue, pausing and continuing, a watchdog trip in the
// middle of a move, the platform's faults — each a clear error, the platform paused.
#include "robot_mover_logic.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "mir_logic_fixture.h"

namespace hubrt::mir_com::test {
namespace {

hub_msgs::RobotMoverCommand command(std::string_view action, std::string_view pose = "") {
  hub_msgs::RobotMoverCommand c;
  c.set_target_type("robot_mover");
  c.set_target_name("mover");
  c.set_action(action);
  c.set_robot_type("MIR100");
  c.set_robot_name("mir100");
  c.set_pose_type(pose.empty() ? "" : "POSITION");
  c.set_pose_name(pose);
  c.set_speed_scal(0.5F);
  c.set_acc_scal(0.5F);
  c.set_goal_toll(0.05F);
  return c;
}

class RobotMoverTest : public MirLogicFixture {
 protected:
  RobotMoverLogic make_logic() {
    auto settings = parse_robot_mover_settings(node("mover"));
    EXPECT_TRUE(settings) << settings.error().message;
    RobotMoverSettings s = *settings;
    s.move_mission = platform_->config().move_mission_guid;
    return RobotMoverLogic(s, make_device());
  }

  long count_sent(std::string_view line) const {
    return std::count(device_->sent().begin(), device_->sent().end(), std::string(line));
  }
};

constexpr std::string_view kPause = R"(PUT /status {"state_id": 4})";
constexpr std::string_view kContinue = R"(PUT /status {"state_id": 3})";

TEST_F(RobotMoverTest, NotOperationalPausesThePlatformOnceAndHoldsIt) {
  RobotMoverLogic logic = make_logic();
  // hubd stopping closes the device, which pauses the platform as its last word.
  EXPECT_EQ(device_->on_close().method, hal::HttpMethod::kPut);
  EXPECT_EQ(device_->on_close().body.view(), R"({"state_id": 4})");
  hub_msgs::RobotMoverState state =
      run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(5));
  EXPECT_EQ(platform_->snapshot().state_id, 4);
  EXPECT_EQ(count_sent(kPause), 1) << "once, not every cycle";
  EXPECT_TRUE(state.safe_hold());
  EXPECT_TRUE(state.answering());
  EXPECT_EQ(state.platform_state(), "Pause");
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
}

TEST_F(RobotMoverTest, MovesToANamedPositionThroughTheMissionQueue) {
  RobotMoverLogic logic = make_logic();
  run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(1));  // answering, paused
  const hub_msgs::RobotMoverCommand move = command("move", "kit_pickup");
  hub_msgs::RobotMoverState state = run(logic, &move, seconds(1));
  EXPECT_TRUE(state.moving()) << errors_text();
  EXPECT_FALSE(state.safe_hold());
  EXPECT_EQ(state.goal_pose(), "kit_pickup");
  EXPECT_EQ(state.mission_state(), "Executing");
  EXPECT_GT(state.x(), 0.1F);
  EXPECT_LT(state.x(), 1.9F);
  EXPECT_EQ(state.actual_pose(), "");
  state = run(logic, &move, seconds(3));
  EXPECT_FALSE(state.moving());
  EXPECT_EQ(state.actual_pose(), "kit_pickup");
  EXPECT_EQ(state.done_action(), "moved");
  EXPECT_EQ(state.mission_state(), "Done");
  EXPECT_NEAR(platform_->snapshot().x, 2.0, 1e-6);
  EXPECT_EQ(count_sent("GET /positions"), 1) << "a repeated command is carried out once";
  EXPECT_EQ(std::count_if(device_->sent().begin(), device_->sent().end(),
                          [](const std::string& s) { return s.starts_with("POST /mission_queue"); }),
            1);
  EXPECT_TRUE(errors_.empty()) << errors_text();
  EXPECT_LT(state.battery(), 90.0F);
}

TEST_F(RobotMoverTest, TheWatchdogPausesAMoveAndTheSameCommandLetsItGoOn) {
  RobotMoverLogic logic = make_logic();
  run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(1));
  const long pauses_before = count_sent(kPause);
  const hub_msgs::RobotMoverCommand move = command("move", "station");
  run(logic, &move, seconds(1));
  ASSERT_EQ(platform_->snapshot().state_id, 5);
  // The planner went silent: the node hands in no command.
  hub_msgs::RobotMoverState state =
      run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(2));
  EXPECT_TRUE(state.safe_hold());
  EXPECT_FALSE(state.moving());
  EXPECT_EQ(platform_->snapshot().state_id, 4);
  EXPECT_EQ(count_sent(kPause), pauses_before + 1);
  const double x = platform_->snapshot().x;
  run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(2));
  EXPECT_EQ(platform_->snapshot().x, x) << "paused: it does not move";
  // The planner is back with the same move: continue (once), and it gets there.
  const long continues_before = count_sent(kContinue);
  state = run(logic, &move, seconds(6));
  EXPECT_EQ(count_sent(kContinue), continues_before + 1);
  EXPECT_EQ(state.actual_pose(), "station") << errors_text();
  EXPECT_NEAR(platform_->snapshot().y, 1.5, 1e-6);
}

TEST_F(RobotMoverTest, PauseAndContinueFollowTheCommand) {
  RobotMoverLogic logic = make_logic();
  run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(1));
  const hub_msgs::RobotMoverCommand go = command("continue");
  hub_msgs::RobotMoverState state = run(logic, &go, seconds(1));
  EXPECT_EQ(platform_->snapshot().state_id, 3);
  EXPECT_EQ(state.done_action(), "continued");
  const hub_msgs::RobotMoverCommand pause = command("pause");
  state = run(logic, &pause, seconds(1));
  EXPECT_EQ(platform_->snapshot().state_id, 4);
  EXPECT_EQ(state.done_action(), "paused");
}

TEST_F(RobotMoverTest, AnUnknownPositionIsAFaultUntilReset) {
  RobotMoverLogic logic = make_logic();
  run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(1));
  const hub_msgs::RobotMoverCommand move = command("move", "nowhere");
  run(logic, &move, seconds(1));
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault);
  EXPECT_TRUE(
      errors_.contains("move failed (reset to clear): GET /positions: the platform has no position named "
                       "'nowhere'"))
      << errors_text();
  logic.reset();
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
}

TEST_F(RobotMoverTest, ThePlatformsErrorIsAFaultAndResetClearsItLeavingItPaused) {
  RobotMoverLogic logic = make_logic();
  const hub_msgs::RobotMoverCommand move = command("move", "station");
  run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(1));
  run(logic, &move, seconds(1));
  platform_->inject_error(3001, "Emergency stop button pressed", clock_.now().mono);
  run(logic, &move, seconds(1));
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault);
  EXPECT_TRUE(errors_.contains(
      "platform in state Error (12), 1 error(s), first: 3001: Emergency stop button pressed"))
      << errors_text();
  logic.reset();
  run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(1));
  EXPECT_EQ(platform_->snapshot().state_id, 4) << "cleared, and held paused while not operational";
  EXPECT_EQ(count_sent(R"(PUT /status {"clear_error": true})"), 1);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk) << errors_text();
}

// Each fault of the REST API gives a clear error; a platform that stops answering makes the node
// recover (not operational), and it comes back by itself.
struct FaultCase {
  DeviceFault fault;
  std::string_view error;
};

class RobotMoverFaultTest : public RobotMoverTest, public ::testing::WithParamInterface<FaultCase> {};

TEST_P(RobotMoverFaultTest, IsAClearErrorAndTheNodeRecovers) {
  RobotMoverLogic logic = make_logic();
  run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(1));
  ASSERT_EQ(logic.condition(), runtime::NodeCondition::kOk);
  device_->set_fault(GetParam().fault);
  hub_msgs::RobotMoverState state =
      run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(4));
  EXPECT_TRUE(errors_.contains(GetParam().error)) << errors_text();
  EXPECT_TRUE(errors_.contains("platform mir (scripted) not answering: no status for")) << errors_text();
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kDevicesMissing);
  EXPECT_FALSE(state.answering());
  EXPECT_TRUE(state.safe_hold());
  // Not answering: the platform's pose and battery are not measured (NaN), not a last value.
  EXPECT_TRUE(std::isnan(state.x()) && std::isnan(state.y()) && std::isnan(state.yaw()));
  EXPECT_TRUE(std::isnan(state.battery()));
  device_->set_fault(DeviceFault::kNone);
  state = run<RobotMoverLogic, hub_msgs::RobotMoverCommand>(logic, nullptr, seconds(2));
  EXPECT_FALSE(std::isnan(state.battery())) << "measured again";
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
  EXPECT_TRUE(errors_.empty()) << errors_text();
  EXPECT_EQ(platform_->snapshot().state_id, 4);
}

std::string fault_name(const ::testing::TestParamInfo<FaultCase>& param) {
  switch (param.param.fault) {
    case DeviceFault::kNone:
      return "none";
    case DeviceFault::kServerError:
      return "server_error";
    case DeviceFault::kUnauthorized:
      return "unauthorized";
    case DeviceFault::kNoAnswer:
      return "no_answer";
    case DeviceFault::kRefused:
      return "refused";
    case DeviceFault::kMalformedJson:
      return "malformed_json";
  }
  return "unknown";
}

INSTANTIATE_TEST_SUITE_P(
    Faults, RobotMoverFaultTest,
    ::testing::Values(
        FaultCase{DeviceFault::kServerError, "GET /status: HTTP 500 (internal server error)"},
        FaultCase{DeviceFault::kUnauthorized, "HTTP 401 (unauthorized: check the board's authorization)"},
        FaultCase{DeviceFault::kNoAnswer, "timeout: no answer within the request timeout"},
        FaultCase{DeviceFault::kRefused, "unavailable: cannot connect (refused or unreachable)"},
        FaultCase{DeviceFault::kMalformedJson, "GET /status: malformed JSON in the answer"}),
    fault_name);

TEST_F(RobotMoverTest, CommandsForAnotherRobotOrWithBadFieldsAreRejected) {
  RobotMoverLogic logic = make_logic();
  runtime::Problem problem;
  hub_msgs::RobotMoverCommand c = command("move", "station");
  EXPECT_TRUE(logic.validate(c.view(), problem));
  c.set_robot_type("UR10");
  EXPECT_FALSE(logic.validate(c.view(), problem));
  EXPECT_EQ(problem.view(), "robot_type must be 'MIR100'");
  c = command("move", "station");
  c.set_robot_name("TARS");
  EXPECT_FALSE(logic.validate(c.view(), problem));
  EXPECT_EQ(problem.view(), "robot_name must be 'mir100' (this node's platform)");
  c = command("move", "");
  EXPECT_FALSE(logic.validate(c.view(), problem));
  c = command("move", "a\"b");
  EXPECT_FALSE(logic.validate(c.view(), problem));
  c = command("pause");
  c.set_speed_scal(1.5F);
  EXPECT_FALSE(logic.validate(c.view(), problem));
  c = command("pause");
  c.set_goal_toll(-1.0F);
  EXPECT_FALSE(logic.validate(c.view(), problem));
}

}  // namespace
}  // namespace hubrt::mir_com::test
