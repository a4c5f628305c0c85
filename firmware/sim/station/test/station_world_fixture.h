// The station model's test world, shared by the model and mobile-platform tests: the station's
// three tools, a manual clock, the RSP ECU's actuators as at the start (lock closed, gripper
// closed) and the lift home, with the moves a scenario makes.
#pragma once

#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hubrt/base/time.h"
#include "hubrt/sim/station/station_model.h"

namespace hubrt::sim::station::testing {

inline constexpr Duration kTravel = std::chrono::milliseconds(300);

// The station's tools, every one in its dock; robot moves take kTravel.
inline StationConfig test_config() {
  StationConfig config;
  config.robot_travel = kTravel;
  for (const char* name : {"ladder_frame_tool", "smart_tool", "filter_tool"}) {
    config.tools.push_back(
        ToolConfig{name, std::string("rsp.tool_id.") + name, std::string("dock.slot.") + name, false});
  }
  return config;
}

class StationWorldTest : public ::testing::Test {
 protected:
  explicit StationWorldTest(StationConfig config) : model_(std::move(config)) {
    model_.observe_valve("rsp.lock_valve", false, now());
    model_.observe_valve("rsp.gripper_valve", true, now());
    model_.observe_lift("lift_drive", 380.0);
  }

  Time now() const { return clock_.now().mono; }
  void pass(Duration d) {
    clock_.advance(d);
    model_.advance(now());
  }
  void command(std::string_view action, std::string_view location = "") {
    auto done = model_.command(action, location, now());
    ASSERT_TRUE(done) << done.error().message;
  }
  void go(std::string_view location) {
    command("move_robot", location);
    pass(kTravel);
    ASSERT_EQ(model_.robot_at(), location);
  }
  void lock(bool open) { model_.observe_valve("rsp.lock_valve", open, now()); }
  void gripper(bool closed) { model_.observe_valve("rsp.gripper_valve", closed, now()); }

  ManualClock clock_;
  StationModel model_;
};

}  // namespace hubrt::sim::station::testing
