// mir_com passes the heartbeat conformance suite in both layouts, with its profile
// (conformance.yaml): hubd on the fake backend with test/mir-sim.yaml (the MiR100 simulator on
// loopback) in this test's own DDS domain, `hubctl conformance` testing it from the wire — among
// its checks the safe state: the platform held paused once the watchdog tripped.
#include <filesystem>
#include <fstream>
#include <string>
#include <string_view>

#include <gtest/gtest.h>

#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

#include "hub_process.h"

namespace hubrt::mir_com {
namespace {

// Generous: sanitizer builds on a loaded 2-core machine.
constexpr auto kSuiteTimeout = std::chrono::seconds(120);

class MirComConformanceTest : public ::testing::TestWithParam<std::string_view> {};

TEST_P(MirComConformanceTest, PassesEveryCheck) {
  const std::string layout(GetParam());
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  std::ifstream in(std::string(HUBRT_MIR_COM_DIR) + "/mir_com.yaml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("layout: node_type");
  ASSERT_NE(at, std::string::npos);
  text.replace(at, 17, "layout: " + layout);
  const auto hub_file = std::filesystem::path(::testing::TempDir()) / ("mir_com-" + layout + ".yaml");
  std::ofstream(hub_file) << text;

  integration::HubProcessOptions options;
  options.board = std::string(HUBRT_MIR_COM_DIR) + "/test/mir-sim.yaml";
  options.hub = hub_file.string();
  auto hub = integration::HubProcess::start(*domain, options);
  ASSERT_TRUE(hub) << hub.error().message;

  test_support::Environment env = domain->env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto suite = test_support::ChildProcess::start(
      HUBRT_HUBCTL_PATH,
      {"conformance", "--hub", "mir_com", "--thresholds", HUBRT_CI_THRESHOLDS, "--duration", "2", "--hold",
       "0.6", "--latency-samples", "30"},
      env);
  ASSERT_TRUE(suite) << suite.error().message;
  auto status = suite->wait(kSuiteTimeout);
  ASSERT_TRUE(status) << status.error().message << "\n" << suite->stderr_text();
  const std::string report = suite->stdout_text() + suite->stderr_text();
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << report << "\n" << hub->output();
  const std::string topics = layout == "hub" ? "1 of 1" : "2 of 2";
  EXPECT_NE(report.find("PASS: " + topics + " State topic(s) conform"), std::string::npos) << report;
  EXPECT_NE(report.find("safe-state fields"), std::string::npos) << report;
}

INSTANTIATE_TEST_SUITE_P(Layouts, MirComConformanceTest,
                         ::testing::Values(std::string_view("node_type"), std::string_view("hub")));

}  // namespace
}  // namespace hubrt::mir_com
