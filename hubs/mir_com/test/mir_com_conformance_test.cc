// mir_com passes the heartbeat conformance suite in both layouts, with its profile
// (conformance.yaml): hubd on the fake backend with boards/host-sim-mir-com.yaml (the MiR100 simulator on
// loopback) in this test's own DDS domain, `hubctl conformance` testing it from the wire — among
// its checks the safe state: the platform held paused once the watchdog tripped.
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hub_conformance_run.h"

namespace hubrt::mir_com {
namespace {

class MirComConformanceTest : public ::testing::TestWithParam<std::string_view> {};

TEST_P(MirComConformanceTest, PassesEveryCheck) {
  const std::string layout(GetParam());
  const std::string dir = HUBRT_MIR_COM_DIR;
  integration::expect_hub_conforms({.hub_dir = dir,
                                    .hub_name = "mir_com",
                                    .board = dir + "/../../boards/host-sim-mir-com.yaml",
                                    .layout = layout,
                                    .hub_file_edits = {},
                                    .state_topics = layout == "hub" ? 1 : 2,
                                    .hubctl = HUBRT_HUBCTL_PATH,
                                    .thresholds = HUBRT_CI_THRESHOLDS});
}

INSTANTIATE_TEST_SUITE_P(Layouts, MirComConformanceTest,
                         ::testing::Values(std::string_view("node_type"), std::string_view("hub")));

}  // namespace
}  // namespace hubrt::mir_com
