// hubd running the Tool ECU (hubd_tool_fixture.h) with its drive and controller falling silent:
// no State shows a device reading older than its validity as current, and fresh readings bring
// the values back.
#include <cmath>

#include "hubd_tool_fixture.h"

namespace hubrt::integration::tool_test {
namespace {

// What a State may never say: a reading older than its validity shown as current. The lift
// drive's readings are valid for answer_within_ms (500 ms in tool_ecu.yaml), the controller's
// status for 350 ms.
std::string stale_shown_as_current(const View& v) {
  std::string out;
  if (v.lift.drive_online && v.lift.reading_age_ms > 500) out += "lift online with a stale reading; ";
  // Unknown numbers are NaN (README, "The wire contract"), never a value that reads like a reading.
  if (!v.lift.drive_online && (v.lift.moving || v.lift.enabled || !std::isnan(v.lift.position_mm) ||
                               !std::isnan(v.lift.speed_mm_s) || v.lift.fault_text != "unknown")) {
    out += "lift offline but drive values shown; ";
  }
  if (v.tool.status_fresh != (v.tool.status_age_ms <= 350)) out += "status_fresh disagrees with its age; ";
  if (!v.tool.status_fresh && (v.tool.controller_alarms != "unknown" ||
                               v.tool.selected_program != "unknown" || !std::isnan(v.tool.torque_nm))) {
    out += "stale controller status shown; ";
  }
  return out;
}

TEST_P(HubdToolTest, StaleDeviceReadingsAreShownAsUnknownAndFreshOnesComeBack) {
  start();
  make_ready();
  order(ToolOrder{"tighten", 1, "ladder_frame_bolt"}, LiftOrder{"move", "home"});
  ASSERT_TRUE(wait_for([](const View& v) {
    return v.tool.result_run_id == 1 && v.tool.selected_program == "ladder_frame_bolt" && v.lift.moving;
  })) << describe();
  EXPECT_TRUE(view_.tool.status_fresh);
  EXPECT_TRUE(view_.lift.drive_online);
  EXPECT_LE(view_.lift.reading_age_ms, 500u);

  // Every State seen from here on is checked (the latest one each time the test looks).
  std::string violations;
  const auto checked = [&](const std::function<bool(const View&)>& predicate) {
    return [&violations, predicate](const View& v) {
      violations += stale_shown_as_current(v);
      return predicate(v);
    };
  };
  sim_fault("tool_bus", "power_off");
  sim_fault("lift_drive", "stop_answering");
  ASSERT_TRUE(wait_for(checked([](const View& v) { return !v.lift.drive_online && !v.tool.status_fresh; })))
      << describe();
  EXPECT_FALSE(view_.lift.moving) << "the drive was moving when it fell silent; nobody knows now";
  EXPECT_EQ(view_.lift.fault_text, "unknown");
  EXPECT_GT(view_.lift.reading_age_ms, 500u);
  EXPECT_NE(view_.lift.errors.find("lift motion unknown: last seen at"), std::string::npos) << describe();
  EXPECT_EQ(view_.lift.errors.find("lift stopped"), std::string::npos) << describe();
  EXPECT_EQ(view_.tool.controller_alarms, "unknown");
  EXPECT_EQ(view_.tool.selected_program, "unknown");
  // The drive's own watchdog (1000 ms after the last request) stops it meanwhile; the hub keeps
  // saying "unknown" until it hears from it.
  const std::uint32_t offline_since = view_.lift.reading_age_ms;
  ASSERT_TRUE(wait_for(checked([&](const View& v) { return v.lift.reading_age_ms > offline_since + 1000; })))
      << describe();
  EXPECT_FALSE(view_.lift.drive_online);

  sim_fault("tool_bus", "power_on");
  sim_fault("lift_drive", "answer");
  ASSERT_TRUE(wait_for(checked([](const View& v) { return v.lift.drive_online && v.tool.status_fresh; })))
      << describe();
  EXPECT_LE(view_.lift.reading_age_ms, 500u);
  EXPECT_GT(view_.lift.position_mm, 0.0F) << "where the drive went on its own";
  ASSERT_TRUE(wait_for(checked([](const View& v) { return v.lift.fault_text == "communication watchdog"; })))
      << "a fresh reading shows why it stopped: " << describe();
  EXPECT_FALSE(view_.lift.moving);
  EXPECT_TRUE(view_.lift.fault);
  EXPECT_EQ(view_.tool.controller_alarms, "");
  EXPECT_NE(view_.tool.selected_program, "unknown");
  EXPECT_EQ(violations, "");
}

}  // namespace
}  // namespace hubrt::integration::tool_test
