// The station model with a manual clock: what the world does when the RSP ECU's valves and the
// lift move and when the robot is sent somewhere, and what the hubs' inputs then show.
#include "hubrt/sim/station/station_model.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "station_world_fixture.h"

namespace hubrt::sim::station {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

using testing::kTravel;
using testing::test_config;

class StationModelTest : public testing::StationWorldTest {
 protected:
  StationModelTest() : StationWorldTest(test_config()) {}

  // Takes `tool` from its slot: open the changer, go there, close it, come back home.
  void take(std::string_view tool) {
    lock(true);
    go(tool);
    lock(false);
    ASSERT_NE(model_.on_robot(), nullptr);
    ASSERT_EQ(model_.on_robot()->name, tool);
  }
  // What the world makes `signal` of `hub` show.
  bool input(HubRole hub, std::string_view signal) {
    for (const WorldInput& in : model_.inputs()) {
      if (in.hub == hub && in.signal == signal) return in.active;
    }
    ADD_FAILURE() << "no input " << signal;
    return false;
  }
  std::string on_robot() const { return model_.on_robot() == nullptr ? "none" : model_.on_robot()->name; }
};

TEST_F(StationModelTest, StartsWithEveryToolDockedAndTheRobotHome) {
  EXPECT_EQ(model_.robot_at(), "home");
  EXPECT_EQ(on_robot(), "none");
  EXPECT_EQ(model_.ladder_frame(), "kit");
  for (const char* tool : {"ladder_frame_tool", "smart_tool", "filter_tool"}) {
    EXPECT_TRUE(input(HubRole::kDock, std::string("dock.slot.") + tool)) << tool;
    EXPECT_FALSE(input(HubRole::kRsp, std::string("rsp.tool_id.") + tool)) << tool;
  }
  EXPECT_EQ(model_.arm(), ArmReading::kHome);
  EXPECT_TRUE(input(HubRole::kTool, "tool.arm.home"));
  EXPECT_FALSE(input(HubRole::kTool, "tool.arm.pre_home"));
  EXPECT_FALSE(input(HubRole::kTool, "tool.arm.out_of_range"));
  EXPECT_THAT(model_.faults(), IsEmpty());
}

TEST_F(StationModelTest, TheRobotArrivesWhenItsTravelTimeIsOver) {
  command("move_robot", "kit");
  EXPECT_EQ(model_.robot_at(), "");
  EXPECT_EQ(model_.robot_moving_to(), "kit");
  pass(kTravel - Duration(1));
  EXPECT_EQ(model_.robot_at(), "");
  pass(Duration(1));
  EXPECT_EQ(model_.robot_at(), "kit");
  EXPECT_EQ(model_.robot_moving_to(), "");
  // Sent where it already is: nothing happens, it does not leave.
  command("move_robot", "kit");
  EXPECT_EQ(model_.robot_at(), "kit");
}

TEST_F(StationModelTest, ATaskThatMakesNoSenseIsRefused) {
  auto nowhere = model_.command("move_robot", "canteen", now());
  ASSERT_FALSE(nowhere);
  EXPECT_THAT(nowhere.error().message,
              HasSubstr("unknown location 'canteen' (the robot can go to: home, kit, "
                        "engine, ladder_frame_tool, smart_tool, filter_tool)"));
  auto dance = model_.command("dance", "", now());
  ASSERT_FALSE(dance);
  EXPECT_THAT(dance.error().message, HasSubstr("unknown action 'dance'"));
  EXPECT_EQ(model_.robot_at(), "home");
}

TEST_F(StationModelTest, AToolAttachesWhenTheLockClosesAtItsSlotAndLeavesItsSlotWithTheRobot) {
  lock(true);  // the planner opens the empty changer
  EXPECT_EQ(on_robot(), "none");
  go("ladder_frame_tool");
  EXPECT_EQ(on_robot(), "none") << "an open changer holds nothing";
  lock(false);
  EXPECT_EQ(on_robot(), "ladder_frame_tool");
  EXPECT_EQ(model_.tool_place(0), ToolPlace::kRobot);
  EXPECT_TRUE(input(HubRole::kRsp, "rsp.tool_id.ladder_frame_tool"));
  EXPECT_TRUE(input(HubRole::kDock, "dock.slot.ladder_frame_tool")) << "still sitting in its slot";
  command("move_robot", "kit");
  EXPECT_FALSE(input(HubRole::kDock, "dock.slot.ladder_frame_tool")) << "lifted out as the robot leaves";
  EXPECT_TRUE(input(HubRole::kRsp, "rsp.tool_id.ladder_frame_tool"));
}

TEST_F(StationModelTest, TheLockClosingAwayFromAToolAttachesNothing) {
  lock(true);
  go("kit");
  lock(false);
  EXPECT_EQ(on_robot(), "none");
  lock(true);
  command("move_robot", "smart_tool");
  lock(false);  // closes while the robot is still on its way
  pass(kTravel);
  EXPECT_EQ(on_robot(), "none");
  EXPECT_EQ(model_.tool_place(1), ToolPlace::kDock);
}

TEST_F(StationModelTest, AToolIsLeftInItsSlotWhenTheLockOpensThere) {
  take("filter_tool");
  go("engine");
  EXPECT_FALSE(input(HubRole::kDock, "dock.slot.filter_tool"));
  go("filter_tool");
  EXPECT_TRUE(input(HubRole::kDock, "dock.slot.filter_tool")) << "seated: the dock sees it before the unlock";
  lock(true);
  EXPECT_EQ(on_robot(), "none");
  EXPECT_EQ(model_.tool_place(2), ToolPlace::kDock);
  EXPECT_FALSE(input(HubRole::kRsp, "rsp.tool_id.filter_tool"));
  go("home");
  EXPECT_TRUE(input(HubRole::kDock, "dock.slot.filter_tool"));
  EXPECT_THAT(model_.faults(), IsEmpty());
}

TEST_F(StationModelTest, UnlockingAwayFromTheDockDropsTheToolAndSaysSo) {
  take("smart_tool");
  go("engine");
  lock(true);
  EXPECT_EQ(on_robot(), "none");
  EXPECT_EQ(model_.tool_place(1), ToolPlace::kDropped);
  EXPECT_THAT(model_.faults(),
              ElementsAre("the smart_tool dropped at the engine: the tool changer opened away "
                          "from its dock slot"));
  EXPECT_FALSE(input(HubRole::kRsp, "rsp.tool_id.smart_tool"));
  EXPECT_FALSE(input(HubRole::kDock, "dock.slot.smart_tool"));
  EXPECT_EQ(model_.arm(), ArmReading::kOutOfRange);
  // A dropped tool is not in its slot: going there and locking takes nothing.
  go("smart_tool");
  lock(false);
  EXPECT_EQ(on_robot(), "none");
  // Only a reset of the world brings it back.
  command("reset");
  EXPECT_EQ(model_.tool_place(1), ToolPlace::kDock);
  EXPECT_EQ(model_.robot_at(), "home");
  EXPECT_THAT(model_.faults(), IsEmpty());
}

TEST_F(StationModelTest, UnlockingOnTheWayDropsTheTool) {
  take("filter_tool");
  command("move_robot", "engine");
  lock(true);
  EXPECT_EQ(model_.tool_place(2), ToolPlace::kDropped);
  EXPECT_THAT(model_.faults(), ElementsAre(HasSubstr("the filter_tool dropped on the way to the engine")));
}

TEST_F(StationModelTest, TheLadderFrameFollowsTheGripper) {
  take("ladder_frame_tool");
  gripper(false);
  go("kit");
  EXPECT_EQ(model_.ladder_frame(), "kit");
  gripper(true);
  EXPECT_EQ(model_.ladder_frame(), "gripper");
  auto restock = model_.command("restock", "", now());
  ASSERT_FALSE(restock) << "the frame in the gripper cannot be replaced";
  EXPECT_THAT(restock.error().message, HasSubstr("holds the ladder frame"));
  go("engine");
  gripper(false);
  EXPECT_EQ(model_.ladder_frame(), "engine");
  EXPECT_THAT(model_.faults(), IsEmpty());
  // A new engine and kit: the frame lies on the kit again.
  go("home");
  command("restock");
  EXPECT_EQ(model_.ladder_frame(), "kit");
}

TEST_F(StationModelTest, ClosingTheGripperWhereNoFrameLiesGrabsNothing) {
  take("ladder_frame_tool");
  gripper(false);
  go("engine");
  gripper(true);
  EXPECT_EQ(model_.ladder_frame(), "kit");
  // The gripper valve of another tool does nothing to the frame.
  gripper(false);
  go("ladder_frame_tool");
  lock(true);
  take("filter_tool");
  go("kit");
  gripper(true);
  EXPECT_EQ(model_.ladder_frame(), "kit");
}

TEST_F(StationModelTest, TheFrameDropsWhereItCannotLie) {
  take("ladder_frame_tool");
  gripper(false);
  go("kit");
  gripper(true);
  go("home");
  gripper(false);
  EXPECT_EQ(model_.ladder_frame(), "dropped");
  EXPECT_THAT(model_.faults(), ElementsAre(HasSubstr("the ladder frame dropped at the home")));
}

TEST_F(StationModelTest, DroppingTheLadderFrameToolDropsTheFrameItHolds) {
  take("ladder_frame_tool");
  gripper(false);
  go("kit");
  gripper(true);
  go("engine");
  lock(true);
  EXPECT_EQ(model_.ladder_frame(), "dropped");
  EXPECT_EQ(model_.faults().size(), 2u);
}

TEST_F(StationModelTest, TheArmSensorsFollowTheSmartTool) {
  // In its holder, the lift decides.
  model_.observe_lift("lift_drive", 350.0);
  EXPECT_EQ(model_.arm(), ArmReading::kPreHome);
  EXPECT_TRUE(input(HubRole::kTool, "tool.arm.pre_home"));
  model_.observe_lift("lift_drive", 250.0);
  EXPECT_EQ(model_.arm(), ArmReading::kOperating) << "floating above the engine";
  EXPECT_FALSE(input(HubRole::kTool, "tool.arm.home"));
  EXPECT_FALSE(input(HubRole::kTool, "tool.arm.pre_home"));
  EXPECT_FALSE(input(HubRole::kTool, "tool.arm.out_of_range"));
  model_.observe_lift("another_lift", 380.0);
  EXPECT_EQ(model_.arm(), ArmReading::kOperating) << "another device's position is not the holder's";
  model_.observe_lift("lift_drive", 380.0);
  EXPECT_EQ(model_.arm(), ArmReading::kHome);
  // On the robot: at the holder as in the holder, above the engine operating, else out of range.
  take("smart_tool");
  EXPECT_EQ(model_.arm(), ArmReading::kHome);
  command("move_robot", "engine");
  EXPECT_EQ(model_.arm(), ArmReading::kOutOfRange) << "on the way";
  pass(kTravel);
  EXPECT_EQ(model_.arm(), ArmReading::kOperating);
  go("kit");
  EXPECT_EQ(model_.arm(), ArmReading::kOutOfRange);
  EXPECT_TRUE(input(HubRole::kTool, "tool.arm.out_of_range"));
}

TEST_F(StationModelTest, NothingMayRunATheToolWhoseLiftIsUnknown) {
  StationModel fresh(test_config());
  EXPECT_EQ(fresh.arm(), ArmReading::kOutOfRange);
  EXPECT_FALSE(fresh.lock_open().has_value());
  EXPECT_FALSE(fresh.lift_mm().has_value());
}

TEST_F(StationModelTest, TheFirstValveObservationOnlySaysWhereItIs) {
  StationConfig config = test_config();
  config.robot_start = "smart_tool";
  StationModel fresh(config);
  fresh.observe_valve("rsp.lock_valve", false, now());  // closed, robot at a full slot
  EXPECT_EQ(fresh.on_robot(), nullptr) << "nothing closed: it was closed already";
  fresh.observe_valve("rsp.lock_valve", true, now());
  fresh.observe_valve("rsp.lock_valve", false, now());
  ASSERT_NE(fresh.on_robot(), nullptr);
  EXPECT_EQ(fresh.on_robot()->name, "smart_tool");
}

TEST_F(StationModelTest, CarryingAToolIntoAnOccupiedSlotIsACollision) {
  take("smart_tool");
  go("filter_tool");
  EXPECT_THAT(model_.faults(),
              ElementsAre("collision: the robot carrying the smart_tool went into the dock slot "
                          "of the filter_tool"));
}

TEST_F(StationModelTest, AToolCanStartOnTheRobot) {
  StationConfig config = test_config();
  config.tools[1].starts_on_robot = true;
  StationModel fresh(config);
  ASSERT_NE(fresh.on_robot(), nullptr);
  EXPECT_EQ(fresh.on_robot()->name, "smart_tool");
  EXPECT_EQ(fresh.tool_place(1), ToolPlace::kRobot);
}

}  // namespace
}  // namespace hubrt::sim::station
