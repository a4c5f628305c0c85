// Faults on the whole simulated station over DDS: each scenario of hubs/station/scenarios/faults/
// injects a fault mid-operation, checks the documented safe state and the reason in error_list,
// then recovers with a reset and a fresh command.
#include "station_scenario.h"

namespace hubrt::integration {
namespace {

// The lift at its shipped speed (100 mm/s): a move outlasts the reaction to a fault (the command
// timeout is 1 s), so the scenarios can see the lift stop short of its target.
StationOptions fault_station(StationLayout layout) {
  StationOptions options = brisk_station(layout);
  options.lift_speed_mm_s = 0;
  return options;
}

TEST(StationFaults, PressureDropsWhileTheFrameIsCarried) {
  expect_scenario_passes(fault_station(StationLayout::kNodeType), "faults/pressure-drop.yaml");
}

TEST(StationFaults, ToolControllerHeartbeatStopsMidRun) {
  expect_scenario_passes(fault_station(StationLayout::kNodeType), "faults/tool-heartbeat.yaml");
}

TEST(StationFaults, LiftDriveFaultsAndStopsAnswering) {
  expect_scenario_passes(fault_station(StationLayout::kNodeType), "faults/lift-drive.yaml");
}

TEST(StationFaults, PlannerStopsSending) {
  expect_scenario_passes(fault_station(StationLayout::kNodeType), "faults/planner-silent.yaml");
}

// The hub layout has its own watchdog on the hub command in front of the nodes'.
TEST(StationFaults, PlannerStopsSendingInTheHubLayout) {
  expect_scenario_passes(fault_station(StationLayout::kHub), "faults/planner-silent.yaml");
}

}  // namespace
}  // namespace hubrt::integration
