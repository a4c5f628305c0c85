// The RSP ECU's outputs after hubd ends in ways no clean shutdown covers, on gpio-sim lines in the
// kernel tier's guest: `kill -9` followed by the unit's ExecStopPost line (read from the shipped
// unit template, packaging/deb/hubd.service.in), and a fatal signal caught by hubd's crash
// handler. Skips outside the tier (tests/kernel/run).
//
// gpio-sim gives a released line the level of its pull (gpio_sim_free() in
// drivers/gpio/gpio-sim.c), so a line's level after its holder is gone is what the holder left as
// the line's bias: the running hubd requests every output with a pull toward its safe level
// (issue 29), and so do --safe-outputs and the crash handler. So after `kill -9` both valves are
// safe before ExecStopPost runs: the gripper valve (safe: grab, active), commanded open, is
// pulled back up. Then the test stands in for a driver that does not keep a released line's pull
// (the gripper dropped open, the lock valve energised, the changer open) before ExecStopPost.
#include <atomic>
#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/types.h>

#include "hubrt/dds/qos.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/kernel_test/environment.h"
#include "hubrt/kernel_test/gpio_sim.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/hub_under_test.h"

#include "rsp_messages.h"

namespace hubrt::kernel_test {
namespace {

using rsp_ecu::RspCommand;
using rsp_ecu::RspState;
using std::chrono::milliseconds;
using std::chrono::seconds;
using std::chrono::steady_clock;

// Generous: the guest runs under software emulation on a busy 2-core host (tests/kernel/README.md).
constexpr auto kPatience = seconds(30);

// boards/rpi4-rsp-ecu.yaml: outputs and the pressure switch.
constexpr unsigned kLockValveLine = 4;      // active high, safe false (closed)
constexpr unsigned kGripperValveLine = 18;  // active high, initial true, safe true (grab)
constexpr unsigned kPressureLine = 19;

std::string read_file(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void replace(std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  ASSERT_NE(at, std::string::npos) << "'" << from << "' not found in:\n" << text;
  text.replace(at, from.size(), to);
}

std::vector<std::string> words(const std::string& line) {
  std::istringstream in(line);
  std::vector<std::string> out;
  for (std::string word; in >> word;) out.push_back(word);
  return out;
}

class HubdSafeOutputsKernelTest : public ::testing::Test {
 protected:
  void SetUp() override {
    HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
    // A chip of its own per test: the pulls a test leaves behind are what the next one checks.
    static std::atomic<unsigned> counter{0};
    const std::string name = fmt::format("hubrt-so{}-{}", ::getpid(), counter++);
    auto chip = ScopedGpioSimChip::create(name, 32);
    ASSERT_TRUE(chip) << chip.error().message;
    chip_.emplace(std::move(*chip));
    write_board(name);
    ASSERT_NO_FATAL_FAILURE(hub_.open("kernel-test-planner"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(command_writer_, "/tool_changer/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/rsp_ecu/rsp/state"));
  }

  void TearDown() override {
    hub_.end_hub();  // kills a hubd still running, so the chip's lines are free to remove it
    if (!board_path_.empty()) std::filesystem::remove(board_path_);
  }

  // The shipped RSP ECU board file with its chip replaced by the test's chip (by label).
  void write_board(const std::string& chip_label) {
    std::string text = read_file(std::string(HUBRT_SOURCE_DIR) + "/boards/rpi4-rsp-ecu.yaml");
    board_path_ = (std::filesystem::temp_directory_path() / (chip_label + ".yaml")).string();
    replace(text, "board: rpi4-rsp-ecu", "board: " + chip_label);
    replace(text, "arch: arm64", "arch: x86_64");
    replace(text, "{label: pinctrl-bcm2711}", "{label: " + chip_label + "}");
    std::ofstream(board_path_) << text;
  }

  const GpioSimChip& chip() const { return chip_->chip(); }

  int line(unsigned offset) {
    auto value = read_value(chip(), offset);
    EXPECT_TRUE(value) << value.error().message;
    return value ? *value : -1;
  }

  void send(const char* action, const char* gripper) {
    RspCommand command{};
    hubrt::msgs::typed::assign(command.target_type, "tool_changer");
    hubrt::msgs::typed::assign(command.target_name, "rsp");
    hubrt::msgs::typed::assign(command.action, action);
    hubrt::msgs::typed::assign(command.gripper, gripper);
    ASSERT_TRUE(command_writer_->write(command).is_ok());
  }

  // Starts hubd as the unit does (backend from the board: linux), brings up the air, clears the
  // pressure failure latched while it was off and commands the gripper open: the gripper line
  // then sits at its unsafe level.
  void start_hub_with_gripper_released() {
    // (start() also waits until hubd reads the commands: one written before would be lost.)
    ASSERT_NO_FATAL_FAILURE(hub_.start(
        {.board = board_path_, .hub = "rsp_ecu", .start_patience = kernel_test::kHubdStartPatience}));
    // hubd requested the switch with a pull-down bias; air comes after that.
    ASSERT_TRUE(set_pull(chip(), kPressureLine, Pull::kUp));
    const auto deadline = steady_clock::now() + kPatience;
    bool released = false;
    for (int round = 0; steady_clock::now() < deadline && !released; ++round) {
      // Resets clear the pressure failure latched before the air came (a reset leaves the
      // gripper as it is); the commands in between open the gripper.
      send(round % 4 == 0 ? "reset" : "lock", "release");
      std::this_thread::sleep_for(milliseconds(200));
      auto gripper = read_value(chip(), kGripperValveLine);
      released = gripper && *gripper == 0;
    }
    ASSERT_TRUE(released) << "the gripper line never went low\nhubd output:\n" << hub_.output();
    EXPECT_EQ(line(kLockValveLine), 0);
  }

  // The ExecStopPost line of packaging/deb/hubd.service.in for this board and hub, with the
  // build's hubd for /usr/bin/hubd.
  std::vector<std::string> exec_stop_post() {
    const std::string unit = read_file(std::string(HUBRT_SOURCE_DIR) + "/packaging/deb/hubd.service.in");
    std::istringstream lines(unit);
    std::vector<std::string> found;
    for (std::string line; std::getline(lines, line);) {
      if (line.rfind("ExecStopPost=", 0) != 0) continue;
      std::string command = line.substr(std::string("ExecStopPost=").size());
      replace(command, "@HUBRT_PKG_BOARD@", board_path_);
      replace(command, "@HUBRT_PKG_HUB@", "rsp_ecu");
      found = words(command);
    }
    EXPECT_FALSE(found.empty()) << "no ExecStopPost= in the unit template";
    if (!found.empty()) {
      EXPECT_EQ(found.front(), "/usr/bin/hubd");
      found.erase(found.begin());
    }
    return found;
  }

  std::optional<ScopedGpioSimChip> chip_;
  std::string board_path_;
  dds::Writer<RspCommand>* command_writer_ = nullptr;
  test_support::StateStream<RspState>* states_ = nullptr;
  test_support::HubUnderTest hub_{kPatience};
};

TEST_F(HubdSafeOutputsKernelTest, AfterKillNineTheUnitsExecStopPostLeavesBothValvesSafe) {
  ASSERT_NO_FATAL_FAILURE(start_hub_with_gripper_released());
  ASSERT_TRUE(hub_.hub().process().signal(SIGKILL));
  auto ended = hub_.hub().process().wait(kPatience);
  ASSERT_TRUE(ended) << ended.error().message;
  ASSERT_TRUE(ended->killed_by(SIGKILL)) << ended->describe();
  // hubd's own requests pulled the lines toward their safe levels: released by the kill, they
  // fell there before anything else ran (before issue 29 the gripper line dropped open here).
  EXPECT_EQ(line(kGripperValveLine), 1) << "the gripper line did not fall back to grab";
  EXPECT_EQ(line(kLockValveLine), 0);
  // The hazard on a driver that forgets a released line's pull: the gripper drops open, and a lock
  // valve line that kept its level would keep the changer open.
  ASSERT_TRUE(set_pull(chip(), kGripperValveLine, Pull::kDown));
  ASSERT_EQ(line(kGripperValveLine), 0);
  ASSERT_TRUE(set_pull(chip(), kLockValveLine, Pull::kUp));
  ASSERT_EQ(line(kLockValveLine), 1);

  const std::vector<std::string> args = exec_stop_post();
  ASSERT_FALSE(args.empty());
  test_support::Environment env{{"HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR},
                                // Any DDS use would fail on this: --safe-outputs uses none.
                                {"CYCLONEDDS_URI", "<CycloneDDS><Broken"}};
  auto safe = test_support::ChildProcess::start(test_support::hubd_path(), args, env);
  ASSERT_TRUE(safe) << safe.error().message;
  auto done = safe->wait(kPatience);
  ASSERT_TRUE(done) << done.error().message;
  const std::string output = safe->stdout_text() + safe->stderr_text();
  EXPECT_TRUE(done->exited_with(0)) << done->describe() << "\n" << output;
  EXPECT_NE(output.find("all 2 outputs driven to their safe levels"), std::string::npos) << output;

  // --safe-outputs has exited and released the lines: they stay at their safe levels.
  EXPECT_EQ(line(kGripperValveLine), 1) << "gripper valve not back at grab\n" << output;
  EXPECT_EQ(line(kLockValveLine), 0) << "lock valve not closed\n" << output;
}

TEST_F(HubdSafeOutputsKernelTest, WithoutHubdRunningItExitsOneNamingEveryOutputItCannotReach) {
  chip_.reset();  // the chip is gone: a board whose GPIO expander is unplugged
  const std::vector<std::string> args = exec_stop_post();
  ASSERT_FALSE(args.empty());
  auto safe = test_support::ChildProcess::start(test_support::hubd_path(), args,
                                                {{"HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR}});
  ASSERT_TRUE(safe) << safe.error().message;
  auto done = safe->wait(kPatience);
  ASSERT_TRUE(done) << done.error().message;
  const std::string output = safe->stdout_text() + safe->stderr_text();
  EXPECT_TRUE(done->exited_with(1)) << done->describe() << "\n" << output;
  EXPECT_NE(output.find("2 of 2 outputs NOT driven safe: rsp.lock_valve, rsp.gripper_valve"),
            std::string::npos)
      << output;
}

TEST_F(HubdSafeOutputsKernelTest, AFatalSignalDrivesTheOutputsSafeBeforeHubdDies) {
  ASSERT_NO_FATAL_FAILURE(start_hub_with_gripper_released());
  ASSERT_TRUE(hub_.hub().process().signal(SIGSEGV));
  auto ended = hub_.hub().process().wait(kPatience);
  ASSERT_TRUE(ended) << ended.error().message;
  // Without a sanitizer the default action kills it; under ASan its own handler (which the crash
  // handler hands over to) reports and exits non-zero.
  EXPECT_TRUE(ended->killed_by(SIGSEGV) || (ended->exit_code && *ended->exit_code != 0)) << ended->describe();
  const std::string output = hub_.output();
  EXPECT_NE(output.find("hubd: fatal signal: GPIO outputs driven to their safe levels"), std::string::npos)
      << output;
  // Released by the dead process, the lines keep the bias the handler gave them.
  EXPECT_EQ(line(kGripperValveLine), 1) << output;
  EXPECT_EQ(line(kLockValveLine), 0) << output;
}

}  // namespace
}  // namespace hubrt::kernel_test
