// The paper's use-case end to end over DDS: the Tool, RSP and Dock ECUs (three hubd on the
// simulation board), the station model (hubsim) and the planner (hubctl play with
// hubs/station/scenarios/use-case.yaml) — the same scenario under both communication layouts —
// and the interlocks between the hubs (interlocks.yaml).
#include "station_scenario.h"

namespace hubrt::integration {
namespace {

TEST(StationUseCase, PassesEndToEndInTheNodeTypeLayout) {
  expect_scenario_passes(StationLayout::kNodeType, "use-case.yaml");
}

TEST(StationUseCase, PassesEndToEndInTheHubLayout) {
  expect_scenario_passes(StationLayout::kHub, "use-case.yaml");
}

// The cross-hub interlocks: the changer stays locked away from the dock (nothing drops), the
// smart tool runs only while the robot holds it above the engine.
TEST(StationUseCase, InterlocksHoldAcrossHubs) {
  expect_scenario_passes(StationLayout::kNodeType, "interlocks.yaml");
}

}  // namespace
}  // namespace hubrt::integration
