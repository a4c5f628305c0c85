// The signal lamp passes the heartbeat conformance suite in both layouts, with its profile
// (conformance.yaml): hubd on the fake backend with test/lamp-sim.yaml in this test's own DDS
// domain, `hubctl conformance` testing it from the wire (tests/integration/hub_conformance_run.h).
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hub_conformance_run.h"

namespace hubrt::signal_lamp {
namespace {

class LampConformanceTest : public ::testing::TestWithParam<std::string_view> {};

TEST_P(LampConformanceTest, PassesEveryCheck) {
  const std::string layout(GetParam());
  const std::string dir = HUBRT_SIGNAL_LAMP_DIR;
  integration::expect_hub_conforms({.hub_dir = dir,
                                    .hub_name = "signal_lamp",
                                    .board = dir + "/test/lamp-sim.yaml",
                                    .layout = layout,
                                    .hub_file_edits = {},
                                    .state_topics = 1,
                                    .hubctl = HUBRT_HUBCTL_PATH,
                                    .thresholds = HUBRT_CI_THRESHOLDS});
}

INSTANTIATE_TEST_SUITE_P(Layouts, LampConformanceTest,
                         ::testing::Values(std::string_view("node_type"), std::string_view("hub")));

}  // namespace
}  // namespace hubrt::signal_lamp
