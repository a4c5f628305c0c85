// hubd running the Tool ECU (hubd_tool_fixture.h): tightenings, the lift, the RSP interlock,
// faults with their safe states and recovery, and the planner going quiet, in both layouts.
#include "hubd_tool_fixture.h"

namespace hubrt::integration::tool_test {
namespace {

TEST_P(HubdToolTest, TightensEachRunIdOnceMovesTheLiftAndObeysTheRspInterlock) {
  start();
  make_ready();
  order(ToolOrder{"tighten", 1, "ladder_frame_bolt"}, LiftOrder{"move", "work"});
  ASSERT_TRUE(wait_for([](const View& v) {
    return v.tool.result_run_id == 1 && v.tool.output == "idle" && v.lift.at == "work";
  })) << describe();
  EXPECT_TRUE(view_.tool.result_ok) << describe();
  EXPECT_EQ(view_.tool.result_counter, 1u);
  EXPECT_TRUE(view_.tool.fresh_msg);
  EXPECT_EQ(view_.tool.echo_action, "tighten");
  EXPECT_EQ(view_.tool.errors, "");
  EXPECT_EQ(view_.lift.errors, "");

  // The planner repeats "tighten 1" (every 100 ms) while the hub runs for a second: still one
  // tightening, in every State of that second.
  ASSERT_TRUE(watch_for(seconds(1), [](const View& v) {
    EXPECT_EQ(v.tool.result_counter, 1u);
    EXPECT_EQ(v.tool.output, "idle");
  })) << describe();

  // The RSP ECU goes silent: its State is lost, which counts as "not allowed".
  rsp_alive(false);
  ASSERT_TRUE(wait_for([](const View& v) { return !v.tool.robot_holds_tool; })) << describe();
  order(ToolOrder{"tighten", 2, "ladder_frame_bolt"});
  ASSERT_TRUE(wait_for([](const View& v) {
    return v.tool.blocked_by.find("robot's grip on the tool unknown") == 0 &&
           v.tool.errors.find("robot state lost: input 'rsp' (/rsp_ecu/rsp/state)") != std::string::npos;
  })) << describe();
  EXPECT_EQ(view_.tool.output, "idle");
  EXPECT_EQ(view_.tool.result_run_id, 1u);
  rsp_alive(true);
  ASSERT_TRUE(wait_for([](const View& v) { return v.tool.result_run_id == 2; })) << describe();
  EXPECT_TRUE(view_.tool.result_ok);
  EXPECT_EQ(view_.tool.result_counter, 2u);

  // A bad command is rejected with its reason; nothing runs.
  order(ToolOrder{"tighten", 3, "wheel_nut"});
  ASSERT_TRUE(wait_for([](const View& v) {
    return v.tool.errors.find("rejected command: unknown program 'wheel_nut'") != std::string::npos;
  })) << describe();
  EXPECT_EQ(view_.tool.result_run_id, 2u);
}

TEST_P(HubdToolTest, ControllerLostAndLiftDriveSilentEndInTheSafeStateAndRecoverAfterReset) {
  start();
  make_ready();
  order(ToolOrder{"loosen", 0, ""}, LiftOrder{"move", "home"});
  ASSERT_TRUE(wait_for([](const View& v) { return v.tool.output == "reverse"; })) << describe();

  sim_fault("tool_bus", "power_off");
  sim_fault("lift_drive", "stop_answering");
  ASSERT_TRUE(wait_for([](const View& v) {
    return v.tool.errors.find("tool controller lost: no heartbeat for") != std::string::npos &&
           v.lift.errors.find("not answering for") != std::string::npos;
  })) << describe();
  EXPECT_EQ(view_.tool.output, "idle");
  EXPECT_FALSE(view_.lift.drive_online);

  sim_fault("tool_bus", "power_on");
  sim_fault("lift_drive", "answer");
  ASSERT_TRUE(wait_for([](const View& v) {
    return v.tool.errors.find("tool controller was lost") != std::string::npos &&
           v.lift.errors.find("stopped answering for a while; send reset to clear") != std::string::npos;
  })) << describe();
  EXPECT_EQ(view_.tool.output, "idle") << "latched until reset";

  order(ToolOrder{"reset", 0, ""}, LiftOrder{"reset", ""});
  ASSERT_TRUE(wait_for([](const View& v) { return v.tool.errors.empty() && v.lift.errors.empty(); }))
      << describe();
  order(ToolOrder{"tighten", 5, "ladder_frame_bolt"}, LiftOrder{"move", "float"});
  ASSERT_TRUE(wait_for([](const View& v) { return v.tool.result_run_id == 5 && v.lift.at == "float"; }))
      << describe();
  EXPECT_TRUE(view_.tool.result_ok) << describe();
}

TEST_P(HubdToolTest, WhenThePlannerStopsTheToolGoesIdleAndTheLiftStops) {
  start();
  make_ready();
  order(ToolOrder{"loosen", 0, ""}, LiftOrder{"move", "home"});
  ASSERT_TRUE(wait_for([](const View& v) { return v.tool.output == "reverse" && v.lift.target == "home"; }))
      << describe();
  planner_goes_quiet();
  ASSERT_TRUE(wait_for([](const View& v) { return !v.tool.fresh_msg && !v.lift.fresh_msg; })) << describe();
  ASSERT_TRUE(wait_for([](const View& v) { return v.tool.output == "idle" && v.lift.target.empty(); }))
      << describe();
  EXPECT_NE(view_.tool.errors.find("command timeout"), std::string::npos) << describe();
  // The drive is read once per cycle (the HAL's asynchronous Modbus, one request per cycle), so the
  // State that first shows the stop carries the reading taken a cycle before it (100 ms at 10 Hz:
  // up to 10 mm at 100 mm/s, its age in reading_age_ms). The position holds from the next reading.
  ASSERT_TRUE(watch_for(milliseconds(250), [](const View&) {})) << describe();
  const float held = view_.lift.position_mm;
  // Unstopped it would move 50 mm while the hub runs for 500 ms (100 mm/s); a few mm allow for the
  // drive's own deceleration.
  ASSERT_TRUE(watch_for(milliseconds(500), [held](const View& v) {
    EXPECT_NEAR(v.lift.position_mm, held, 5.0) << "stopped";
  })) << describe();
}

INSTANTIATE_TEST_SUITE_P(BothLayouts, HubdToolTest, ::testing::Values(Layout::kNodeType, Layout::kHub),
                         [](const ::testing::TestParamInfo<Layout>& param) {
                           return param.param == Layout::kHub ? std::string("HubLayout")
                                                              : std::string("NodeTypeLayout");
                         });

}  // namespace
}  // namespace hubrt::integration::tool_test
