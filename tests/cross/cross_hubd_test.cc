// The cross-built hubd keeps the wire contract when a program built for another machine talks to
// it: the target hubd runs under qemu-user (this test is a target program too, so ChildProcess puts
// the emulator in front of hubd) on the simulation board, and the build machine's own hubctl
// checks it over loopback DDS, in this test's private domain — as a laptop checks a Pi.
#include <signal.h>

#include <chrono>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "hubrt/test_support/child_process.h"
#include "hubrt/test_support/test_domain.h"

namespace hubrt::cross_test {
namespace {

using std::chrono::seconds;
using test_support::ChildProcess;
using test_support::Environment;
using test_support::TestDomain;

// qemu-user runs hubd several times slower than natively, on a 2-core machine that builds and
// tests in parallel: start-up (Cyclone DDS, the fake backend) takes seconds there, not ms.
constexpr auto kHubStartup = seconds(60);
// hubctl itself is native; a full conformance run against one State topic takes ~15 s of
// measuring with the phase lengths below. The rest is slack for the loaded machine.
constexpr auto kHubctlTimeout = seconds(240);

Environment hub_environment(const TestDomain& domain) {
  Environment env = domain.env();
  // Cross builds have no source tree compiled in: boards/ and hubs/ come from here.
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  return env;
}

class CrossHubd : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto hub = ChildProcess::start(HUBRT_HUBD_PATH, {"--board", "host-sim", "--hub", "dock_ecu"},
                                   hub_environment(*domain_));
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(hub_->wait_for_output("running hub", kHubStartup)) << "hubd did not start:\n" << hub_output();
  }

  void TearDown() override {
    if (!hub_) return;
    // hubd stops on SIGTERM as under systemd; a crash at shutdown would show here.
    ASSERT_TRUE(hub_->signal(SIGTERM));
    auto status = hub_->wait(kHubStartup);
    ASSERT_TRUE(status) << status.error().message << "\n" << hub_output();
    EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hub_output();
  }

  std::string hub_output() const { return hub_ ? hub_->stdout_text() + hub_->stderr_text() : std::string(); }

  // Runs the host's hubctl to completion.
  struct Run {
    test_support::ExitStatus status;
    std::string out;
    std::string err;
  };
  Run hubctl(const std::vector<std::string>& args) {
    Run run;
    auto child = ChildProcess::start(HUBRT_HOST_HUBCTL, args, hub_environment(*domain_));
    if (!child) {
      ADD_FAILURE() << child.error().message;
      return run;
    }
    auto status = child->wait(kHubctlTimeout);
    if (!status) {
      ADD_FAILURE() << "hubctl " << args.front() << " did not finish: " << status.error().message << "\n"
                    << child->stderr_text();
      return run;
    }
    run.status = *status;
    run.out = child->stdout_text();
    run.err = child->stderr_text();
    return run;
  }

  std::optional<TestDomain> domain_;
  std::optional<ChildProcess> hub_;
};

std::string failed_checks(const nlohmann::json& report) {
  std::string out;
  for (const auto& target : report.value("targets", nlohmann::json::array())) {
    for (const auto& check : target["checks"]) {
      if (check["verdict"] == "FAIL") {
        out += fmt::format("{}: {} (threshold {}) {}\n", check["check"].get<std::string>(),
                           check["text"].get<std::string>(), check["threshold"].get<std::string>(),
                           check["detail"].get<std::string>());
      }
    }
  }
  return out;
}

TEST_F(CrossHubd, PassesTheHostHubctlsConformanceSuite) {
  const Run run = hubctl({"conformance", "--json", "--hub", "dock_ecu", "--thresholds", HUBRT_QEMU_THRESHOLDS,
                          "--duration", "3", "--hold", "1", "--latency-samples", "30"});
  const auto report = nlohmann::json::parse(run.out, nullptr, /*allow_exceptions=*/false);
  ASSERT_FALSE(report.is_discarded()) << "no JSON report:\n" << run.out << run.err << hub_output();
  EXPECT_TRUE(run.status.exited_with(0)) << run.status.describe() << "\n"
                                         << failed_checks(report) << run.err << hub_output();
  EXPECT_EQ(report["passed"], true);
  ASSERT_EQ(report["targets"].size(), 1U) << run.out;
  const auto& target = report["targets"][0];
  // Learned from the emulated hub's /diagnostics: the types and QoS match across machines.
  EXPECT_EQ(target["rate_source"], "/diagnostics");
  std::set<std::string> ran;
  for (const auto& check : target["checks"]) ran.insert(check["check"].get<std::string>());
  // Each phase ran: a skipped phase cannot pass for the cross-built hub.
  for (const char* check :
       {"rate_error", "seq_gaps", "echo_all", "watchdog", "no_stale_reapply", "got_reset"}) {
    EXPECT_TRUE(ran.contains(check)) << "the suite did not check " << check << "\n" << run.out;
  }
}

TEST_F(CrossHubd, HostHubctlMeasuresItsRateAndSeesItsEcho) {
  // Rate: the Dock ECU's 10 Hz heartbeat, seen by the native hubctl for 3 s. The bounds are wide
  // (qemu on a loaded machine delays single cycles), but a hub at another rate, or one that
  // stalls for a second, falls outside; loopback DDS with reliable QoS loses no State.
  const Run hz = hubctl({"hz", "/dock_ecu/dock/state", "--window", "3", "--json"});
  ASSERT_TRUE(hz.status.exited_with(0)) << hz.status.describe() << "\n" << hz.err << hub_output();
  const auto rate = nlohmann::json::parse(hz.out, nullptr, false);
  ASSERT_FALSE(rate.is_discarded()) << hz.out;
  EXPECT_GT(rate["rate_hz"].get<double>(), 8.0) << hz.out;
  EXPECT_LT(rate["rate_hz"].get<double>(), 12.0) << hz.out;
  EXPECT_GE(rate["samples"].get<int>(), 20) << hz.out;
  EXPECT_EQ(rate["seq_gaps"], 0) << hz.out;

  // Echo: the planner's way — the command repeated at 10 Hz; the hub must echo it verbatim and
  // mark it fresh. Before anyone commands it, the echo is empty.
  auto sender = ChildProcess::start(HUBRT_HOST_HUBCTL,
                                    {"send", "/dock/command", "target_type=dock", "target_name=dock",
                                     "action=monitor", "--rate", "10", "--quiet"},
                                    hub_environment(*domain_));
  ASSERT_TRUE(sender) << sender.error().message;
  const Run echo = hubctl({"echo", "/dock_ecu/dock/state", "--json", "--count", "40"});
  (void)sender->signal(SIGTERM);
  ASSERT_TRUE(echo.status.exited_with(0)) << echo.status.describe() << "\n" << echo.err << hub_output();
  bool echoed = false;
  std::istringstream lines(echo.out);
  for (std::string line; std::getline(lines, line);) {
    const auto state = nlohmann::json::parse(line, nullptr, false);
    ASSERT_FALSE(state.is_discarded()) << line;
    const auto& command = state["echo"];
    if (command["action"] == "monitor" && command["target_type"] == "dock" &&
        command["target_name"] == "dock" && state["fresh_msg"] == true) {
      echoed = true;
      break;
    }
  }
  EXPECT_TRUE(echoed) << "no State echoed the command within 40 States:\n"
                      << echo.out << sender->stderr_text() << hub_output();
}

}  // namespace
}  // namespace hubrt::cross_test
