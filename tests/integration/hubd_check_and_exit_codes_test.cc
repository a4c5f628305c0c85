// `hubd --check` validates files only: no device, no network (it passes with no network at all and
// with a real board whose GPIO chip does not exist here). And every exit status of the table in
// hubrt/base/exit_codes.h, for hubd and hubctl, as a script or systemd sees it.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <regex>
#include <sstream>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/base/exit_codes.h"
#include "hubrt/dds/domain.h"
#include "hubrt/dds/ports.h"
#include "hubrt/test_support/hub_process.h"

namespace hubrt::integration {
using test_support::Finished;
namespace {

namespace fs = std::filesystem;
using std::chrono::seconds;

// Generous: start-up under sanitizers on a loaded 2-core machine.
constexpr auto kPatience = seconds(60);

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs `program args` to its end with the config folder of this source tree.
Finished run_program(const std::string& program, const std::vector<std::string>& args,
                     const test_support::Environment& extra = {}) {
  test_support::Environment env = extra;
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto child = test_support::ChildProcess::start(program, args, env);
  EXPECT_TRUE(child) << child.error().message;
  if (!child) return {};
  auto status = child->wait(kPatience);
  EXPECT_TRUE(status) << status.error().message;
  if (!status) return {};
  return Finished{*status, child->stdout_text() + child->stderr_text()};
}

class HubdCheckTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / fmt::format("hubrt-check-{}", getpid());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

// In a network namespace of its own nothing but a downed loopback exists: joining DDS or starting
// the lift drive's Modbus simulator on 127.0.0.1 fails there (old --check assembled the whole hub
// and failed), validating files does not.
TEST_F(HubdCheckTest, PassesWithNoNetworkAtAll) {
  const Finished probe = run_program("unshare", {"-n", "true"});
  if (!probe.status.exited_with(0)) {
    GTEST_SKIP() << "cannot make a network namespace here (unshare -n: " << probe.status.describe()
                 << "; needs root or CAP_SYS_ADMIN): " << probe.output;
  }
  for (const std::string hub : {"tool_ecu", "rsp_ecu", "dock_ecu"}) {
    std::vector<std::string> args{"-n"};
    for (const std::string& word : test_support::target_emulator()) args.push_back(word);
    for (const std::string& arg : {test_support::hubd_path(), std::string("--board"), std::string("host-sim"),
                                   std::string("--hub"), hub, std::string("--check")}) {
      args.push_back(arg);
    }
    const Finished f = run_program("unshare", args);
    EXPECT_TRUE(f.status.exited_with(0)) << hub << ": " << f.status.describe() << "\n" << f.output;
    EXPECT_NE(f.output.find(fmt::format("configuration OK: hub '{}'", hub)), std::string::npos) << f.output;
  }
}

// On a real board (linux backend) --check opens no device and no socket, seen in the system calls
// it makes (strace): old --check assembled the hub — on a Pi it requested every GPIO output at its
// `initial` level (on the RSP board that energises the gripper valve), looked for GPIO chips by
// label (scanning /dev), opened CAN and Modbus, joined DDS (AF_INET, AF_NETLINK sockets).
TEST_F(HubdCheckTest, OpensNoDeviceAndNoSocketOnARealBoard) {
  if (!test_support::target_emulator().empty()) {
    GTEST_SKIP() << "hubd runs under an emulator here (HUBRT_TARGET_EMULATOR): strace would trace the "
                    "emulator's own calls; the default suite runs this check natively";
  }
  const Finished probe = run_program("strace", {"-o", "/dev/null", "true"});
  if (!probe.status.exited_with(0)) {
    GTEST_SKIP() << "strace cannot run here (" << probe.status.describe() << "): " << probe.output;
  }
  for (const std::string board : {"rpi4-rsp-ecu", "rpi4-tool-ecu", "rpi4-dock-ecu"}) {
    const fs::path trace = dir_ / (board + ".strace");
    // LeakSanitizer cannot run under ptrace; leaks are not what this test looks at.
    const Finished f = run_program("strace",
                                   {"-f", "-qq", "-e", "trace=openat,open,socket", "-o", trace.string(),
                                    test_support::hubd_path(), "--board", board, "--check"},
                                   {{"ASAN_OPTIONS", "detect_leaks=0"}});
    EXPECT_TRUE(f.status.exited_with(0)) << board << ": " << f.status.describe() << "\n" << f.output;
    EXPECT_NE(f.output.find("with the linux backend"), std::string::npos) << f.output;
    const std::string calls = read_text(trace);
    ASSERT_FALSE(calls.empty()) << "no trace written to " << trace;
    for (const std::string forbidden : {"socket(AF_INET", "socket(AF_NETLINK", "socket(AF_CAN", "\"/dev\", ",
                                        "\"/dev/gpiochip", "\"/dev/tty"}) {
      EXPECT_EQ(calls.find(forbidden), std::string::npos)
          << board << ": --check made a call with '" << forbidden << "':\n"
          << calls;
    }
  }
}

// --check still validates what it can without devices: the hub's needs against the board.
TEST_F(HubdCheckTest, StillRefusesAHubTheBoardCannotCarry) {
  std::string hub = read_text(fs::path(HUBRT_SOURCE_DIR) / "hubs" / "rsp_ecu" / "rsp_ecu.yaml");
  const std::string wiring = "lock_valve: rsp.lock_valve";
  ASSERT_NE(hub.find(wiring), std::string::npos) << "the test's assumption about the hub file";
  hub.replace(hub.find(wiring), wiring.size(), "lock_valve: rsp.no_such_valve");
  const fs::path path = dir_ / "rsp_ecu.yaml";
  std::ofstream(path) << hub;
  const Finished f =
      run_program(test_support::hubd_path(), {"--board", "rpi4-rsp-ecu", "--hub", path.string(), "--check"});
  EXPECT_TRUE(f.status.exited_with(exit_codes::kUsage)) << f.status.describe() << "\n" << f.output;
  EXPECT_NE(f.output.find("rsp.no_such_valve"), std::string::npos) << f.output;
}

// A domain whose ports meet this host's ephemeral port range can be joined from another domain by
// a planner that does not announce its domain id (hubrt/dds/ports.h): hubd says so at start,
// unsecured, and names the way out; a domain outside the range gets no such warning.
TEST_F(HubdCheckTest, WarnsOfADomainWhosePortsMeetTheEphemeralRange) {
  const dds::PortRange ephemeral = dds::ephemeral_port_range();
  std::optional<std::uint32_t> inside;
  std::optional<std::uint32_t> outside;
  for (std::uint32_t id = 0; id <= dds::kMaxDomainId; ++id) {
    auto& slot = dds::disjoint(dds::domain_port_band(id), ephemeral) ? outside : inside;
    if (!slot) slot = id;
  }
  const auto check_in = [](std::uint32_t id) {
    return run_program(test_support::hubd_path(), {"--board", "host-sim", "--hub", "dock_ecu", "--domain",
                                                   std::to_string(id), "--check"});
  };
  if (inside) {
    const Finished f = check_in(*inside);
    EXPECT_TRUE(f.status.exited_with(0)) << f.status.describe() << "\n" << f.output;
    EXPECT_NE(f.output.find(fmt::format("DDS domain {}'s UDP ports", *inside)), std::string::npos)
        << f.output;
    EXPECT_NE(f.output.find("docs/deploy.md"), std::string::npos) << f.output;
  }
  if (outside) {
    const Finished f = check_in(*outside);
    EXPECT_TRUE(f.status.exited_with(0)) << f.status.describe() << "\n" << f.output;
    EXPECT_EQ(f.output.find("'s UDP ports"), std::string::npos) << f.output;
  }
  EXPECT_TRUE(inside || outside);
}

// And what building the nodes would refuse, checked without building them: a hub-layout node name
// the hub's messages have no field for, a subscription of the wrong message type.
TEST_F(HubdCheckTest, StillRefusesWhatBuildingTheNodesWouldRefuse) {
  struct Case {
    std::string hub;
    std::string from;
    std::string to;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"dock_ecu",
       "layout: node_type\nnodes:\n  dock:", "layout: hub\nnodes:\n  dok:", "has no field for node 'dok'"},
      {"rsp_ecu", "type: hub_msgs/msg/DockState", "type: hub_msgs/msg/RspState",
       "input 'dock' must be a hub_msgs/msg/DockState, not hub_msgs/msg/RspState"},
  };
  for (const Case& c : cases) {
    std::string hub = read_text(fs::path(HUBRT_SOURCE_DIR) / "hubs" / c.hub / (c.hub + ".yaml"));
    ASSERT_NE(hub.find(c.from), std::string::npos) << "the test's assumption about " << c.hub << ".yaml";
    hub.replace(hub.find(c.from), c.from.size(), c.to);
    const fs::path path = dir_ / (c.hub + ".yaml");
    std::ofstream(path) << hub;
    const Finished f =
        run_program(test_support::hubd_path(), {"--board", "host-sim", "--hub", path.string(), "--check"});
    EXPECT_TRUE(f.status.exited_with(exit_codes::kUsage)) << c.hub << ": " << f.status.describe() << "\n"
                                                          << f.output;
    EXPECT_NE(f.output.find(c.message), std::string::npos) << f.output;
  }
}

// hubd's command-line errors: CLI11 says 105/106/109 on its own; the table says 2, the status the
// unit does not restart.
TEST(HubdExitCodes, CommandLineErrorsAreUsageErrors) {
  const std::vector<std::vector<std::string>> bad = {
      {"--board", "host-sim", "--backend", "quantum"},  // CLI11: ValidationError, 105
      {"--hub", "dock_ecu"},                            // RequiredError (no --board), 106
      {"--board", "host-sim", "--no-such-option"},      // ExtrasError, 109
      {"--board", "host-sim", "--rate", "0"},           // out of range, 105
      {"--board", "host-sim", "--hub", "dock_ecu", "--log-level", "chatty"},
  };
  for (const auto& args : bad) {
    const Finished f = run_program(test_support::hubd_path(), args);
    EXPECT_TRUE(f.status.exited_with(exit_codes::kUsage))
        << fmt::format("hubd {}: ", fmt::join(args, " ")) << f.status.describe() << "\n"
        << f.output;
  }
}

TEST(HubdExitCodes, HelpExitsZeroAndPrintsTheTable) {
  const Finished f = run_program(test_support::hubd_path(), {"--help"});
  EXPECT_TRUE(f.status.exited_with(exit_codes::kOk)) << f.status.describe();
  EXPECT_NE(f.output.find(exit_codes::kHelpFooter), std::string::npos) << f.output;
}

TEST(HubdExitCodes, AConfigurationErrorIsAUsageError) {
  const Finished f = run_program(test_support::hubd_path(), {"--board", "no-such-board", "--check"});
  EXPECT_TRUE(f.status.exited_with(exit_codes::kUsage)) << f.status.describe() << "\n" << f.output;
}

// The systemd unit does not restart exactly the table's usage status.
TEST(HubdExitCodes, TheUnitPreventsRestartsOnUsageErrorsOnly) {
  const std::string unit = read_text(fs::path(HUBRT_SOURCE_DIR) / "packaging" / "deb" / "hubd.service.in");
  std::smatch match;
  ASSERT_TRUE(std::regex_search(unit, match, std::regex(R"(\nRestartPreventExitStatus=([^\n]*)\n)"))) << unit;
  EXPECT_EQ(match[1].str(), std::to_string(exit_codes::kUsage));
  EXPECT_NE(unit.find("\nRestart=on-failure\n"), std::string::npos) << unit;
}

TEST(HubctlExitCodes, FollowTheSameTable) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  const test_support::Environment env = domain->env();
  struct Case {
    std::vector<std::string> args;
    int status;
  };
  const std::vector<Case> cases = {
      {{"--help"}, exit_codes::kOk},
      {{}, exit_codes::kUsage},              // no command
      {{"frobnicate"}, exit_codes::kUsage},  // unknown command
      {{"hz", "/dock_ecu/dock/state", "--no-such"}, exit_codes::kUsage},
      {{"hz", "not a topic", "--loopback", "--timeout", "0.1"}, exit_codes::kUsage},
      // Nothing publishes in this private domain: measured nothing, a failure.
      {{"hz", "/dock_ecu/dock/state", "--type", "hub_msgs/msg/DockState", "--window", "1", "--loopback"},
       exit_codes::kFailure},
  };
  for (const Case& c : cases) {
    const Finished f = run_program(HUBRT_HUBCTL_PATH, c.args, env);
    EXPECT_TRUE(f.status.exited_with(c.status))
        << fmt::format("hubctl {}: ", fmt::join(c.args, " ")) << f.status.describe() << "\n"
        << f.output;
  }
  const Finished help = run_program(HUBRT_HUBCTL_PATH, {"--help"}, env);
  EXPECT_NE(help.output.find(exit_codes::kHelpFooter), std::string::npos) << help.output;
}

}  // namespace
}  // namespace hubrt::integration
