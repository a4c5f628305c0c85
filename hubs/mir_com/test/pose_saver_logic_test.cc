// The pose saver under a manual clock against the simulated platform: "update" saves the pose the
// platform has after the command (once per command), a refusal is a fault until reset.
#include "pose_saver_logic.h"

#include <algorithm>
#include <cmath>

#include "mir_logic_fixture.h"

namespace hubrt::mir_com::test {
namespace {

hub_msgs::PoseSaverCommand pose_command(std::string_view action, std::string_view pose = "") {
  hub_msgs::PoseSaverCommand c;
  c.set_target_type("pose_saver");
  c.set_target_name("poses");
  c.set_action(action);
  c.set_robot_type("MIR100");
  c.set_robot_name("mir100");
  c.set_pose_type("POSITION");
  c.set_pose_name(pose);
  return c;
}

class PoseSaverTest : public MirLogicFixture {
 protected:
  PoseSaverLogic make_logic() {
    auto settings = parse_pose_saver_settings(node("poses"));
    EXPECT_TRUE(settings) << settings.error().message;
    return PoseSaverLogic(*settings, make_device());
  }
  long posts() const {
    return std::count_if(device_->sent().begin(), device_->sent().end(),
                         [](const std::string& s) { return s.starts_with("POST /positions"); });
  }
};

TEST_F(PoseSaverTest, UpdateSavesTheCurrentPoseOncePerCommand) {
  PoseSaverLogic logic = make_logic();
  hub_msgs::PoseSaverState state =
      run<PoseSaverLogic, hub_msgs::PoseSaverCommand>(logic, nullptr, seconds(1));
  EXPECT_FALSE(state.busy());
  EXPECT_EQ(posts(), 0) << "nothing is saved without a command";
  EXPECT_TRUE(std::isnan(state.x()) && std::isnan(state.y()) && std::isnan(state.yaw()))
      << "no pose saved yet";
  const hub_msgs::PoseSaverCommand update = pose_command("update", "here");
  state = run(logic, &update, seconds(2));
  EXPECT_EQ(state.done_action(), "updated") << errors_text();
  EXPECT_EQ(state.saved_pose(), "here");
  EXPECT_EQ(state.x(), 0.0F) << "the platform's pose, measured";
  EXPECT_FALSE(state.busy());
  EXPECT_EQ(posts(), 1) << "a repeated command is carried out once";
  const auto post = std::find_if(device_->sent().begin(), device_->sent().end(),
                                 [](const std::string& s) { return s.starts_with("POST /positions"); });
  ASSERT_NE(post, device_->sent().end());
  EXPECT_EQ(post->find(R"(POST /positions {"name": "here", "pos_x": 0.000, "pos_y": 0.000,)"), 0u) << *post;
  // "idle" between: the same name is saved again.
  const hub_msgs::PoseSaverCommand idle = pose_command("idle");
  state = run(logic, &idle, seconds(1));
  EXPECT_EQ(state.done_action(), "");
  run(logic, &update, seconds(1));
  EXPECT_EQ(posts(), 2);
  EXPECT_TRUE(errors_.empty()) << errors_text();
}

TEST_F(PoseSaverTest, ARefusedSaveIsAFaultUntilReset) {
  PoseSaverLogic logic = make_logic();
  run<PoseSaverLogic, hub_msgs::PoseSaverCommand>(logic, nullptr, seconds(1));
  device_->set_fault(DeviceFault::kServerError);
  const hub_msgs::PoseSaverCommand update = pose_command("update", "here");
  // The status GET fails as well: the save waits for a fresh pose, nothing is posted.
  run(logic, &update, seconds(1));
  EXPECT_EQ(posts(), 0);
  EXPECT_TRUE(errors_.contains("HTTP 500")) << errors_text();
  device_->set_fault(DeviceFault::kNone);
  hub_msgs::PoseSaverState state = run(logic, &update, seconds(1));
  EXPECT_EQ(state.done_action(), "updated") << errors_text();
  // A name the platform refuses: the simulator takes 1 to 40 characters; a map it does not know.
  logic.reset();
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
}

TEST_F(PoseSaverTest, NotOperationalAbandonsASaveBeforeItsPost) {
  PoseSaverLogic logic = make_logic();
  run<PoseSaverLogic, hub_msgs::PoseSaverCommand>(logic, nullptr, seconds(1));
  device_->set_fault(DeviceFault::kNoAnswer);
  const hub_msgs::PoseSaverCommand update = pose_command("update", "here");
  cycle(logic, &update);  // GET /status submitted, never answered
  run<PoseSaverLogic, hub_msgs::PoseSaverCommand>(logic, nullptr, seconds(3));
  device_->set_fault(DeviceFault::kNone);
  const hub_msgs::PoseSaverState state =
      run<PoseSaverLogic, hub_msgs::PoseSaverCommand>(logic, nullptr, seconds(2));
  EXPECT_FALSE(state.busy());
  EXPECT_EQ(posts(), 0);
}

}  // namespace
}  // namespace hubrt::mir_com::test
