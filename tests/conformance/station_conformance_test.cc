// Every hub of the simulated station passes the heartbeat conformance suite: the station's hubd
// processes run on the fake backend in this test's own DDS domain, and `hubctl conformance` tests
// each one from the wire, as an engineer would against a real cell.
#include <unistd.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <ostream>
#include <set>
#include <string_view>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/test_domain.h"

#include "failed_checks.h"

namespace hubrt::conformance_test {
namespace {

// The hubs of the simulated station, as `hubd --board host-sim --hub <hub>` runs them with their
// shipped configuration. Adding a hub to the station is adding its line here.
struct StationHub {
  const char* hub;   // hub type and, with the shipped configuration, its instance name
  int state_topics;  // State topics it publishes (node-type layout: one per node)
  bool hub_layout;   // run with `layout: hub` (one State topic) instead of the shipped layout
};
// gtest names each test with the parameter printed: print the hub, not the struct's bytes.
[[maybe_unused]] void PrintTo(const StationHub& hub, std::ostream* out) {
  *out << hub.hub << (hub.hub_layout ? " (hub layout)" : "");
}

constexpr StationHub kStation[] = {
    {"dock_ecu", 1, false},
    {"tool_ecu", 2, false},
    {"rsp_ecu", 1, false},
};
// The same station in the hub layout: the hub's watchdog must drive every node's safe state in
// the same cycle as it trips (the profiles declare the safe-state fields it checks).
constexpr StationHub kStationHubLayout[] = {
    {"dock_ecu", 1, true},
    {"tool_ecu", 1, true},
    {"rsp_ecu", 1, true},
};

// The shipped hub file of `hub` with `layout: hub`, written into `dir`.
std::string hub_layout_file(const std::string& hub, const std::filesystem::path& dir) {
  std::ifstream in(fmt::format("{}/hubs/{}/{}.yaml", HUBRT_SOURCE_DIR, hub, hub));
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const auto at = text.find("layout: node_type");
  EXPECT_NE(at, std::string::npos) << hub << ".yaml has no 'layout: node_type' line";
  if (at != std::string::npos) text.replace(at, 17, "layout: hub");
  const auto path = dir / (hub + ".yaml");
  std::ofstream(path) << text;
  return path.string();
}

// What a full run must have checked on every State topic, so that a phase silently skipped fails.
// Constant-initialized (a std::set here would be built before main and could throw there).
constexpr auto kExpectedChecks = std::to_array<std::string_view>({"first_state",
                                                                  "rate_error",
                                                                  "jitter_p50",
                                                                  "jitter_p99",
                                                                  "jitter_max",
                                                                  "fresh_before",
                                                                  "fresh_while_commanded",
                                                                  "t_plus_grows",
                                                                  "t_plus_restarts",
                                                                  "repeats_silent",
                                                                  "echo_all",
                                                                  "echo_p50",
                                                                  "echo_p99",
                                                                  "watchdog",
                                                                  "watchdog_error",
                                                                  "safe_state",
                                                                  "no_stale_reapply",
                                                                  "same_command_restarts",
                                                                  "got_reset",
                                                                  "seq_gaps"});

// Generous: hubctl's own run takes ~10 s per State topic; a sanitizer build on a loaded machine
// may take several times that.
constexpr auto kSuiteTimeout = std::chrono::seconds(150);

struct SuiteRun {
  test_support::ExitStatus status;
  std::string stdout_text;
  std::string stderr_text;
  nlohmann::json report;
};

class StationConformance : public ::testing::TestWithParam<StationHub> {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    // The whole station, so that each hub is tested amid the traffic of the others.
    const bool hub_layout = GetParam().hub_layout;
    if (hub_layout) {
      dir_ = std::filesystem::temp_directory_path() /
             fmt::format("hubrt-station-conformance-{}-{}", getpid(), GetParam().hub);
      std::filesystem::create_directories(dir_);
    }
    for (const StationHub& station_hub : hub_layout ? kStationHubLayout : kStation) {
      test_support::HubProcessOptions options;
      options.hub = hub_layout ? hub_layout_file(station_hub.hub, dir_) : station_hub.hub;
      auto hub = test_support::HubProcess::start(*domain_, options);
      ASSERT_TRUE(hub) << hub.error().message;
      hubs_.push_back(std::move(*hub));
    }
  }

  void TearDown() override {
    hubs_.clear();
    if (!dir_.empty()) std::filesystem::remove_all(dir_);
  }

  std::string hub_output() const {
    std::string out;
    for (const auto& hub : hubs_) out += hub.output();
    return out;
  }

  // Runs hubctl conformance with the CI bounds and short phases, plus `args`.
  SuiteRun run_suite(std::vector<std::string> args) {
    std::vector<std::string> all = {"conformance",       "--json", "--thresholds", HUBRT_CI_THRESHOLDS,
                                    "--duration",        "2",      "--hold",       "0.6",
                                    "--latency-samples", "30"};
    all.insert(all.end(), args.begin(), args.end());
    test_support::Environment env = domain_->env();
    env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
    SuiteRun run;
    auto child = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, all, env);
    if (!child) {
      ADD_FAILURE() << child.error().message;
      return run;
    }
    auto status = child->wait(kSuiteTimeout);
    if (!status) {
      ADD_FAILURE() << "hubctl conformance did not finish: " << status.error().message << "\n"
                    << child->stderr_text();
      return run;
    }
    run.status = *status;
    run.stdout_text = child->stdout_text();
    run.stderr_text = child->stderr_text();
    run.report = nlohmann::json::parse(run.stdout_text, nullptr, /*allow_exceptions=*/false);
    return run;
  }

  std::optional<test_support::TestDomain> domain_;
  std::filesystem::path dir_;
  std::vector<test_support::HubProcess> hubs_;
};

TEST_P(StationConformance, PassesTheHeartbeatConformanceSuite) {
  const StationHub& hub = GetParam();
  const SuiteRun run = run_suite({"--hub", hub.hub});
  ASSERT_FALSE(run.report.is_discarded()) << "no JSON report:\n" << run.stdout_text << run.stderr_text;
  EXPECT_TRUE(run.status.exited_with(0)) << run.status.describe() << "\n"
                                         << failed_checks(run.report) << run.stderr_text << hub_output();
  EXPECT_EQ(run.report["passed"], true);
  ASSERT_EQ(run.report["targets"].size(), static_cast<std::size_t>(hub.state_topics)) << run.stdout_text;
  for (const auto& target : run.report["targets"]) {
    EXPECT_EQ(target["hub"], hub.hub);
    // Learned from the wire (/diagnostics), not given on the command line.
    EXPECT_EQ(target["rate_source"], "/diagnostics");
    EXPECT_EQ(target["command_timeout_source"], "/diagnostics");
    std::set<std::string, std::less<>> ran;
    for (const auto& check : target["checks"]) ran.insert(check["check"].get<std::string>());
    for (const std::string_view expected : kExpectedChecks) {
      EXPECT_TRUE(ran.contains(expected)) << target["state_topic"] << " did not check " << expected;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Station, StationConformance, ::testing::ValuesIn(kStation),
                         [](const ::testing::TestParamInfo<StationHub>& param) {
                           return std::string(param.param.hub);
                         });
INSTANTIATE_TEST_SUITE_P(StationHubLayout, StationConformance, ::testing::ValuesIn(kStationHubLayout),
                         [](const ::testing::TestParamInfo<StationHub>& param) {
                           return std::string(param.param.hub);
                         });

// The suite's verdict reaches the exit code: told to expect twice the Dock's rate, it fails the
// rate (and only the heartbeat phase runs, to keep this short).
TEST(StationConformanceVerdict, AHubThatDoesNotMeetTheExpectationFails) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  test_support::HubProcessOptions options;
  options.hub = "dock_ecu";
  auto hub = test_support::HubProcess::start(*domain, options);
  ASSERT_TRUE(hub) << hub.error().message;
  test_support::Environment env = domain->env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto child = test_support::ChildProcess::start(
      HUBRT_HUBCTL_PATH,
      {"conformance", "--json", "--hub", "dock_ecu", "--rate", "20", "--phases", "heartbeat", "--duration",
       "1", "--thresholds", HUBRT_CI_THRESHOLDS},
      env);
  ASSERT_TRUE(child) << child.error().message;
  auto status = child->wait(kSuiteTimeout);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(1)) << status->describe() << "\n"
                                      << child->stdout_text() << child->stderr_text();
  const auto report = nlohmann::json::parse(child->stdout_text(), nullptr, false);
  ASSERT_FALSE(report.is_discarded()) << child->stdout_text();
  EXPECT_EQ(report["passed"], false);
  bool rate_failed = false;
  for (const auto& check : report["targets"][0]["checks"]) {
    if (check["check"] == "rate_error") rate_failed = check["verdict"] == "FAIL";
  }
  EXPECT_TRUE(rate_failed) << child->stdout_text();
}

}  // namespace
}  // namespace hubrt::conformance_test
