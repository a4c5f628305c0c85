// The operator hub passes the heartbeat conformance suite in both layouts, with its profile
// (conformance.yaml): hubd on the fake backend with test/operator-sim.yaml in this test's own DDS
// domain, `hubctl conformance` testing it from the wire.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

#include "hub_process.h"

namespace hubrt::operator_hub {
namespace {

// Generous: sanitizer builds on a loaded 2-core machine; a run takes about 8 s.
constexpr auto kSuiteTimeout = std::chrono::seconds(90);

class OperatorConformanceTest : public ::testing::TestWithParam<std::string_view> {};

TEST_P(OperatorConformanceTest, PassesEveryCheck) {
  const std::string layout(GetParam());
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  // The shipped hub file, in the layout under test.
  std::ifstream in(std::string(HUBRT_OPERATOR_HUB_DIR) + "/operator_hub.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("layout: node_type");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 17, "layout: " + layout);
  // The copy lives elsewhere: the test allow-list by its absolute path.
  const auto list = text.find("allow_list: operators.list");
  ASSERT_NE(list, std::string::npos);
  text.replace(list, 26, "allow_list: " + std::string(HUBRT_OPERATOR_HUB_DIR) + "/test/operators.list");
  const auto hub_file = std::filesystem::path(::testing::TempDir()) / ("operator_hub-" + layout + ".yaml");
  std::ofstream(hub_file) << text;

  integration::HubProcessOptions options;
  options.board = std::string(HUBRT_OPERATOR_HUB_DIR) + "/test/operator-sim.yaml";
  options.hub = hub_file.string();
  auto hub = integration::HubProcess::start(*domain, options);
  ASSERT_TRUE(hub) << hub.error().message;

  test_support::Environment env = domain->env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto suite = test_support::ChildProcess::start(
      HUBRT_HUBCTL_PATH,
      {"conformance", "--hub", "operator_hub", "--thresholds", HUBRT_CI_THRESHOLDS, "--duration", "2",
       "--hold", "0.6", "--latency-samples", "30"},
      env);
  ASSERT_TRUE(suite) << suite.error().message;
  auto status = suite->wait(kSuiteTimeout);
  ASSERT_TRUE(status) << status.error().message << "\n" << suite->stderr_text();
  const std::string report = suite->stdout_text() + suite->stderr_text();
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << report << "\n" << hub->output();
  EXPECT_NE(report.find("PASS: 1 of 1 State topic(s) conform"), std::string::npos) << report;
  // The profile's safe state was checked, not skipped.
  EXPECT_NE(report.find("safe-state fields"), std::string::npos) << report;
}

INSTANTIATE_TEST_SUITE_P(Layouts, OperatorConformanceTest,
                         ::testing::Values(std::string_view("node_type"), std::string_view("hub")));

}  // namespace
}  // namespace hubrt::operator_hub
