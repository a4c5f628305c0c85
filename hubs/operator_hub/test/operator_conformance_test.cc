// The operator hub passes the heartbeat conformance suite in both layouts, with its profile
// (conformance.yaml): hubd on the fake backend with boards/host-sim-operator-hub.yaml in this test's own DDS
// domain, `hubctl conformance` testing it from the wire. The hub file's copy lives in a temporary
// folder, so its allow-list is named by its absolute path.
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hub_conformance_run.h"

namespace hubrt::operator_hub {
namespace {

class OperatorConformanceTest : public ::testing::TestWithParam<std::string_view> {};

TEST_P(OperatorConformanceTest, PassesEveryCheck) {
  const std::string layout(GetParam());
  const std::string dir = HUBRT_OPERATOR_HUB_DIR;
  integration::expect_hub_conforms(
      {.hub_dir = dir,
       .hub_name = "operator_hub",
       .board = dir + "/../../boards/host-sim-operator-hub.yaml",
       .layout = layout,
       .hub_file_edits = {{"allow_list: operators.list", "allow_list: " + dir + "/test/operators.list"}},
       .state_topics = 1,
       .hubctl = HUBRT_HUBCTL_PATH,
       .thresholds = HUBRT_CI_THRESHOLDS});
}

INSTANTIATE_TEST_SUITE_P(Layouts, OperatorConformanceTest,
                         ::testing::Values(std::string_view("node_type"), std::string_view("hub")));

}  // namespace
}  // namespace hubrt::operator_hub
