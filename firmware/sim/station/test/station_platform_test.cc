// The mobile platform in the station model, with a manual clock: the kit (and the ladder frame on
// it) is at the station only while the platform stands at its station position.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/sim/station/station_model.h"

#include "station_world_fixture.h"

namespace hubrt::sim::station {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::IsEmpty;

using testing::kTravel;

constexpr Duration kPlatformTimeout = milliseconds(1000);

StationConfig config_with_platform(bool platform) {
  StationConfig config = testing::test_config();
  if (platform) {
    config.mobile_platform =
        MobilePlatformConfig{"/mir_com/mover/state", "", "station", "kit", kPlatformTimeout};
  }
  return config;
}

class StationPlatformTest : public testing::StationWorldTest {
 protected:
  explicit StationPlatformTest(bool platform = true) : StationWorldTest(config_with_platform(platform)) {}

  void take_frame_tool() {
    lock(true);
    go("ladder_frame_tool");
    lock(false);
    ASSERT_NE(model_.on_robot(), nullptr);
  }
  // The platform's State, as the mir_com hub's RobotMoverState says it.
  void platform(bool moving, std::string_view pose) { model_.observe_platform({moving, pose}, now()); }
  void platform_at_station() { platform(false, "station"); }
};

class StationWithoutPlatformTest : public StationPlatformTest {
 protected:
  StationWithoutPlatformTest() : StationPlatformTest(false) {}
};

TEST_F(StationWithoutPlatformTest, TheKitIsAlwaysThere) {
  EXPECT_EQ(model_.kit(), KitPlace::kAtStation);
  EXPECT_EQ(model_.ladder_frame(), "kit");
  // A platform's State is none of its business.
  platform(true, "");
  pass(kPlatformTimeout * 5);
  EXPECT_EQ(model_.kit(), KitPlace::kAtStation);
  EXPECT_EQ(model_.ladder_frame(), "kit");
  go("kit");
}

TEST_F(StationPlatformTest, UntilThePlatformIsHeardThereIsNoKit) {
  EXPECT_EQ(model_.kit(), KitPlace::kUnknown);
  EXPECT_EQ(to_string(model_.kit()), "unknown");
  EXPECT_EQ(model_.ladder_frame(), "away") << "the frame comes with the kit";
  auto to_kit = model_.command("move_robot", "kit", now());
  ASSERT_FALSE(to_kit);
  EXPECT_EQ(to_kit.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(to_kit.error().message, HasSubstr("no kit at the station: the mobile platform is not there"));
  EXPECT_EQ(model_.robot_at(), "home") << "a refused move goes nowhere";
  go("engine");  // elsewhere it goes
}

TEST_F(StationPlatformTest, ThePlatformArrivingBringsTheKitWithTheFrameOnIt) {
  platform(true, "");  // on its way
  EXPECT_EQ(model_.kit(), KitPlace::kAway);
  EXPECT_EQ(to_string(model_.kit()), "away");
  platform(false, "kit_pickup");  // stands elsewhere
  EXPECT_EQ(model_.kit(), KitPlace::kAway);
  EXPECT_EQ(model_.ladder_frame(), "away");
  platform(true, "");
  platform_at_station();
  EXPECT_EQ(model_.kit(), KitPlace::kAtStation);
  EXPECT_EQ(to_string(model_.kit()), "at_station");
  EXPECT_EQ(model_.ladder_frame(), "kit");
  // Its State again and again: nothing new arrives.
  take_frame_tool();
  gripper(false);
  go("kit");
  gripper(true);
  ASSERT_EQ(model_.ladder_frame(), "gripper");
  platform_at_station();
  EXPECT_EQ(model_.ladder_frame(), "gripper");
  go("engine");
  gripper(false);
  EXPECT_EQ(model_.ladder_frame(), "engine");
  EXPECT_THAT(model_.faults(), IsEmpty());
}

TEST_F(StationPlatformTest, ThePlatformLeavingTakesTheKitAndAFrameStillOnIt) {
  platform_at_station();
  ASSERT_EQ(model_.ladder_frame(), "kit");
  platform(true, "");
  EXPECT_EQ(model_.kit(), KitPlace::kAway);
  EXPECT_EQ(model_.ladder_frame(), "away");
  EXPECT_THAT(model_.faults(), IsEmpty()) << "the robot was not at the kit";
  // It comes back with a new kit and frame.
  platform_at_station();
  EXPECT_EQ(model_.ladder_frame(), "kit");
  // Standing at another position is leaving too.
  platform(false, "home");
  EXPECT_EQ(model_.kit(), KitPlace::kAway);
  EXPECT_EQ(model_.ladder_frame(), "away");
}

TEST_F(StationPlatformTest, AFramePutOnTheEngineStaysWhenThePlatformLeaves) {
  platform_at_station();
  take_frame_tool();
  gripper(false);
  go("kit");
  gripper(true);
  go("engine");
  gripper(false);
  platform(true, "");
  EXPECT_EQ(model_.ladder_frame(), "engine");
  EXPECT_THAT(model_.faults(), IsEmpty());
}

TEST_F(StationPlatformTest, ThePlatformLeavingWhileTheRobotIsAtTheKitIsACollision) {
  platform_at_station();
  go("kit");
  platform(true, "");
  EXPECT_THAT(model_.faults(),
              ElementsAre("collision: the mobile platform left while the robot was at the kit"));
  EXPECT_EQ(model_.ladder_frame(), "away");
}

TEST_F(StationPlatformTest, AFramePutDownAtTheKitWithNoKitDrops) {
  platform_at_station();
  take_frame_tool();
  gripper(false);
  go("kit");
  gripper(true);  // holds the frame at the kit
  platform(true, "");
  EXPECT_EQ(model_.ladder_frame(), "gripper") << "the robot holds it";
  ASSERT_EQ(model_.faults().size(), 1U);
  gripper(false);  // nothing to lie on
  EXPECT_EQ(model_.ladder_frame(), "dropped");
  ASSERT_EQ(model_.faults().size(), 2U);
  EXPECT_THAT(model_.faults()[1], HasSubstr("the ladder frame dropped at the kit"));
}

TEST_F(StationPlatformTest, ALostStateIsAnUnknownPlatformAndTheKitCountsAsGone) {
  platform_at_station();
  pass(kPlatformTimeout);
  EXPECT_EQ(model_.kit(), KitPlace::kAtStation) << "not yet longer than the timeout";
  pass(Duration(1));
  EXPECT_EQ(model_.kit(), KitPlace::kUnknown);
  EXPECT_EQ(model_.ladder_frame(), "away");
  EXPECT_FALSE(model_.command("move_robot", "kit", now()));
  platform_at_station();  // heard again, at the station: a kit is there
  EXPECT_EQ(model_.kit(), KitPlace::kAtStation);
  EXPECT_EQ(model_.ladder_frame(), "kit");
}

TEST_F(StationPlatformTest, RestockPutsTheFrameOnTheKitOnlyWhenTheKitIsThere) {
  command("restock");
  EXPECT_EQ(model_.ladder_frame(), "away");
  platform_at_station();
  take_frame_tool();
  gripper(false);
  go("kit");
  gripper(true);
  go("engine");
  gripper(false);
  ASSERT_EQ(model_.ladder_frame(), "engine");
  command("restock");
  EXPECT_EQ(model_.ladder_frame(), "kit");
}

TEST_F(StationPlatformTest, ResetKeepsTheKitWhereThePlatformIs) {
  platform_at_station();
  go("kit");
  platform(true, "");
  ASSERT_THAT(model_.faults(), ::testing::SizeIs(1));
  command("reset");
  EXPECT_THAT(model_.faults(), IsEmpty());
  EXPECT_EQ(model_.robot_at(), "home");
  EXPECT_EQ(model_.kit(), KitPlace::kAway);
  EXPECT_EQ(model_.ladder_frame(), "away");
  platform_at_station();
  command("reset");
  EXPECT_EQ(model_.kit(), KitPlace::kAtStation);
  EXPECT_EQ(model_.ladder_frame(), "kit");
}

}  // namespace
}  // namespace hubrt::sim::station
