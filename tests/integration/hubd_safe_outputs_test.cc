// hubd --safe-outputs as a process on the simulation board (fake backend). What it can show here
// is limited: the simulated valves live in the hubd process that drove them and die with it, so
// after a kill -9 there is nothing left to make safe. What it does show: it runs while no hubd
// runs (right after one was killed), joins no DDS domain, takes exactly the hub's outputs and
// exits 0. The lines themselves are checked on gpio-sim in the kernel tier
// (tests/kernel/hubd/hubd_safe_outputs_kernel_test.cc).
#include <csignal>

#include <gtest/gtest.h>

#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
using test_support::Finished;
using test_support::HubProcess;
using test_support::HubProcessOptions;
namespace {

using std::chrono::seconds;

// Cyclone refuses this configuration: anything that joined DDS would fail.
constexpr const char* kBrokenDdsConfig = "<CycloneDDS><Domain><General><Nonsense";

Finished run_without_dds(const std::vector<std::string>& args) {
  const test_support::Environment env{{"HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR},
                                      {"CYCLONEDDS_URI", kBrokenDdsConfig}};
  auto child = test_support::ChildProcess::start(test_support::hubd_path(), args, env);
  EXPECT_TRUE(child) << child.error().message;
  if (!child) return {};
  auto status = child->wait(seconds(60));  // an ASan hubd on a busy machine: seconds
  EXPECT_TRUE(status) << status.error().message;
  return Finished{status ? *status : test_support::ExitStatus{}, child->stdout_text() + child->stderr_text()};
}

TEST(HubdSafeOutputs, AfterAKilledHubdItDrivesTheHubsOutputsWithoutDds) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto hub = HubProcess::start(*domain, HubProcessOptions{"host-sim", "rsp_ecu", {}, {}});
  ASSERT_TRUE(hub) << hub.error().message;
  ASSERT_TRUE(hub->process().signal(SIGKILL));
  auto killed = hub->process().wait(seconds(30));
  ASSERT_TRUE(killed) << killed.error().message;
  ASSERT_TRUE(killed->killed_by(SIGKILL)) << killed->describe();

  const Finished f = run_without_dds({"--board", "host-sim", "--hub", "rsp_ecu", "--safe-outputs"});
  EXPECT_TRUE(f.status.exited_with(0)) << f.status.describe() << "\n" << f.output;
  EXPECT_NE(f.output.find("rsp.lock_valve: driven to its safe level (inactive)"), std::string::npos)
      << f.output;
  EXPECT_NE(f.output.find("rsp.gripper_valve: driven to its safe level (active)"), std::string::npos)
      << f.output;
  EXPECT_NE(f.output.find("all 2 outputs driven to their safe levels"), std::string::npos) << f.output;
  EXPECT_EQ(f.output.find("tool.run_forward"), std::string::npos) << "another hub's output:\n" << f.output;
}

TEST(HubdSafeOutputs, TheBrokenDdsConfigurationDoesStopAHubdThatUsesDds) {
  // The control for the test above: the same environment makes a hubd that joins DDS fail at
  // once (a plain run; --check joins no network either, so it would pass).
  const Finished f = run_without_dds({"--board", "host-sim", "--hub", "rsp_ecu"});
  EXPECT_TRUE(f.status.exited_with(1)) << f.status.describe() << "\n" << f.output;
}

TEST(HubdSafeOutputs, ABoardNotWiredForTheHubExitsTwo) {
  const Finished f = run_without_dds({"--board", "rpi4-dock-ecu", "--hub", "rsp_ecu", "--safe-outputs"});
  EXPECT_TRUE(f.status.exited_with(2)) << f.status.describe() << "\n" << f.output;
}

}  // namespace
}  // namespace hubrt::integration
