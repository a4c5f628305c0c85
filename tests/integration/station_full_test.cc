// The paper's whole story end to end over DDS (hubs/station/scenarios/full-use-case.yaml): five
// hubd — the robot cell's Tool (with the operator interlock), RSP and Dock ECUs, the MiR100's
// mir_com on its REST simulator, the operator hub with its simulated RFID reader and confirm
// button — hubsim with the mobile platform, and the planner (hubctl play): the MiR brings the kit,
// a tightening is refused while nobody is verified, the operator badges in and confirms three
// steps with the button, the cell assembles, the MiR leaves. Under both communication layouts.
#include "station_scenario.h"

namespace hubrt::integration {
namespace {

StationOptions full_station(StationLayout layout) {
  StationOptions options = brisk_station(layout);
  options.full = true;
  return options;
}

TEST(StationFullUseCase, PassesEndToEndInTheNodeTypeLayout) {
  expect_scenario_passes(full_station(StationLayout::kNodeType), "full-use-case.yaml");
}

TEST(StationFullUseCase, PassesEndToEndInTheHubLayout) {
  expect_scenario_passes(full_station(StationLayout::kHub), "full-use-case.yaml");
}

}  // namespace
}  // namespace hubrt::integration
