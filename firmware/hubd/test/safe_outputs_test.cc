// hubd --safe-outputs, without a process: which outputs it takes from the shipped board and hub
// files, that it opens nothing else and each output at its safe level, how it waits for a line a
// killed hubd still holds, and that every failure is named. The real lines are checked in the
// kernel tier (tests/kernel/hubd/hubd_safe_outputs_kernel_test.cc).
#include "safe_outputs.h"

#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include "hubrt/assembly/fake_simulation.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/linux/gpiod_lines.h"

namespace hubrt::hubd {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

std::string source(const std::string& relative) {
  return std::string(HUBRT_SOURCE_DIR) + "/" + relative;
}

struct Loaded {
  hal::BoardConfig board;
  config::HubConfig hub;
};

Loaded load(const std::string& board, const std::string& hub) {
  auto b = hal::load_board(source("boards/" + board + ".yaml"));
  EXPECT_TRUE(b) << b.error().message;
  auto h = config::load_hub_config(source("hubs/" + hub + "/" + hub + ".yaml"));
  EXPECT_TRUE(h) << h.error().message;
  return Loaded{b ? *b : hal::BoardConfig{}, h ? *h : config::HubConfig{}};
}

std::vector<std::string> signals(const std::vector<hal::DigitalOutputConfig>& outputs) {
  std::vector<std::string> out;
  out.reserve(outputs.size());
  for (const auto& o : outputs) out.push_back(o.signal);
  return out;
}

TEST(SafeOutputConfigs, RspEcuTakesBothValvesAtTheirSafeLevelsBiasedTowardThem) {
  const Loaded files = load("rpi4-rsp-ecu", "rsp_ecu");
  auto outputs = safe_output_configs(files.board, files.hub);
  ASSERT_TRUE(outputs) << outputs.error().message;
  ASSERT_THAT(signals(*outputs), ElementsAre("rsp.lock_valve", "rsp.gripper_valve"));
  for (const auto& o : *outputs) {
    const hal::BoardOutput* wired = files.board.find_output(o.signal);
    ASSERT_NE(wired, nullptr);
    EXPECT_EQ(o.safe, wired->config.safe) << o.signal;
    EXPECT_EQ(o.initial, o.safe) << o.signal << ": opening it must drive nothing but the safe level";
    EXPECT_TRUE(o.bias_toward_safe) << o.signal;
    EXPECT_EQ(o.chip, wired->config.chip);
    EXPECT_EQ(o.line, wired->config.line);
  }
  EXPECT_FALSE((*outputs)[0].safe);  // the lock closed
  EXPECT_TRUE((*outputs)[1].safe);   // the gripper holding
}

TEST(SafeOutputConfigs, ToolEcuTakesOnlyTheRunLinesNotTheBuses) {
  const Loaded files = load("rpi4-tool-ecu", "tool_ecu");
  auto outputs = safe_output_configs(files.board, files.hub);
  ASSERT_TRUE(outputs) << outputs.error().message;
  EXPECT_THAT(signals(*outputs), ElementsAre("tool.run_forward", "tool.run_reverse"));
}

TEST(SafeOutputConfigs, OnTheSimulationBoardOnlyTheHubsOwnOutputs) {
  const Loaded files = load("host-sim", "dock_ecu");
  auto dock = safe_output_configs(files.board, files.hub);
  ASSERT_TRUE(dock) << dock.error().message;
  EXPECT_TRUE(dock->empty()) << "the Dock ECU has no outputs; host-sim has the other hubs' four";
}

TEST(SafeOutputConfigs, ABoardNotWiredForTheHubIsAConfigurationError) {
  const Loaded files = load("rpi4-dock-ecu", "rsp_ecu");
  auto outputs = safe_output_configs(files.board, files.hub);
  ASSERT_FALSE(outputs);
  EXPECT_EQ(outputs.error().code, ErrorCode::kFailedPrecondition);
  EXPECT_THAT(outputs.error().message, HasSubstr("rsp_ecu"));
}

// --- drive_outputs_safe against a backend that records what is opened -----------------------

struct Line {
  hal::DigitalOutputConfig opened_with;
  std::vector<bool> writes;
};

class RecordingOutput final : public hal::DigitalOutput {
 public:
  RecordingOutput(Line& line, bool fail_writes) : line_(line), fail_writes_(fail_writes) {}

 private:
  Status do_write(bool active) noexcept override {
    line_.writes.push_back(active);
    return fail_writes_ ? Status(ErrorCode::kUnavailable) : Status::ok();
  }
  [[nodiscard]] bool do_safe_value() const noexcept override { return line_.opened_with.safe; }
  Line& line_;
  bool fail_writes_;
};

class RecordingBackend final : public hal::Backend {
 public:
  std::map<std::string, int> busy_for;  // signal -> opens that fail kBusy before one succeeds
  std::map<std::string, ErrorCode> refuse;
  std::map<std::string, bool> fail_writes;
  std::map<std::string, int> open_attempts;
  std::map<std::string, Line> lines;

  Expected<std::unique_ptr<hal::DigitalInput>> open_input(const hal::DigitalInputConfig& c) override {
    ADD_FAILURE() << "--safe-outputs opened input " << c.signal;
    return make_error(ErrorCode::kInternal, "no inputs here");
  }
  Expected<std::unique_ptr<hal::DigitalOutput>> open_output(const hal::DigitalOutputConfig& c) override {
    ++open_attempts[c.signal];
    if (busy_for[c.signal] > 0) {
      --busy_for[c.signal];
      return make_error(ErrorCode::kBusy, c.signal + ": line 4 of gpiochip0 is busy, held by 'hubrt'");
    }
    if (refuse.contains(c.signal)) return make_error(refuse[c.signal], c.signal + ": GPIO chip not found");
    Line& line = lines[c.signal];
    line.opened_with = c;
    return std::unique_ptr<hal::DigitalOutput>(
        std::make_unique<RecordingOutput>(line, fail_writes[c.signal]));
  }
  Expected<std::unique_ptr<hal::CanBus>> open_can(const hal::CanConfig& c) override {
    ADD_FAILURE() << "--safe-outputs opened CAN bus " << c.bus;
    return make_error(ErrorCode::kInternal, "no CAN here");
  }
  Expected<std::unique_ptr<hal::ModbusClient>> open_modbus(const hal::ModbusConfig& c) override {
    ADD_FAILURE() << "--safe-outputs opened Modbus device " << c.device;
    return make_error(ErrorCode::kInternal, "no Modbus here");
  }
};

class DriveOutputsSafe : public ::testing::Test {
 protected:
  DriveOutputsSafe() : log_("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(text_)) {
    const Loaded files = load("rpi4-rsp-ecu", "rsp_ecu");
    auto outputs = safe_output_configs(files.board, files.hub);
    EXPECT_TRUE(outputs);
    if (outputs) outputs_ = *outputs;
  }
  SafeOutputsReport drive(const BusyRetry& retry = {}) {
    return drive_outputs_safe(
        backend_, outputs_, retry, [this](Duration d) { slept_.push_back(d); }, log_);
  }

  std::ostringstream text_;
  spdlog::logger log_;
  std::vector<hal::DigitalOutputConfig> outputs_;
  RecordingBackend backend_;
  std::vector<Duration> slept_;
};

TEST_F(DriveOutputsSafe, OpensEachOutputAtItsSafeLevelAndWritesItNothingElse) {
  const SafeOutputsReport report = drive();
  EXPECT_THAT(report.driven, ElementsAre("rsp.lock_valve", "rsp.gripper_valve"));
  EXPECT_TRUE(report.failures.empty());
  ASSERT_EQ(backend_.lines.size(), 2U);
  const Line& lock = backend_.lines["rsp.lock_valve"];
  EXPECT_FALSE(lock.opened_with.initial);
  EXPECT_THAT(lock.writes, ElementsAre(false));
  const Line& gripper = backend_.lines["rsp.gripper_valve"];
  EXPECT_TRUE(gripper.opened_with.initial);
  EXPECT_THAT(gripper.writes, ElementsAre(true));
  EXPECT_TRUE(slept_.empty());
  EXPECT_THAT(text_.str(), HasSubstr("rsp.gripper_valve: driven to its safe level (active)"));
}

TEST_F(DriveOutputsSafe, WaitsForALineAKilledHubdStillHoldsForAMoment) {
  backend_.busy_for["rsp.lock_valve"] = 3;
  const SafeOutputsReport report = drive(BusyRetry{5, std::chrono::milliseconds(50)});
  EXPECT_THAT(report.driven, ElementsAre("rsp.lock_valve", "rsp.gripper_valve"));
  EXPECT_EQ(backend_.open_attempts["rsp.lock_valve"], 4);
  EXPECT_EQ(slept_, std::vector<Duration>(3, std::chrono::milliseconds(50)));
}

TEST_F(DriveOutputsSafe, GivesUpOnALineStillBusyAfterTheRetriesAndNamesIt) {
  backend_.busy_for["rsp.lock_valve"] = 1000;
  const SafeOutputsReport report = drive(BusyRetry{5, std::chrono::milliseconds(50)});
  EXPECT_EQ(backend_.open_attempts["rsp.lock_valve"], 5) << "bounded: a live holder must not be fought";
  EXPECT_EQ(slept_.size(), 4U);
  EXPECT_THAT(report.driven, ElementsAre("rsp.gripper_valve")) << "the other output is still driven";
  ASSERT_EQ(report.failures.size(), 1U);
  EXPECT_THAT(report.failures[0], HasSubstr("rsp.lock_valve: line 4 of gpiochip0 is busy, held by 'hubrt'"));
  EXPECT_THAT(text_.str(), HasSubstr("NOT SAFE: rsp.lock_valve"));
}

TEST_F(DriveOutputsSafe, OtherOpenErrorsAreNotRetriedAndAFailedWriteIsAFailure) {
  backend_.refuse["rsp.lock_valve"] = ErrorCode::kNotFound;
  backend_.fail_writes["rsp.gripper_valve"] = true;
  const SafeOutputsReport report = drive();
  EXPECT_EQ(backend_.open_attempts["rsp.lock_valve"], 1);
  EXPECT_TRUE(report.driven.empty());
  ASSERT_EQ(report.failures.size(), 2U);
  EXPECT_THAT(report.failures[0], HasSubstr("rsp.lock_valve: GPIO chip not found"));
  EXPECT_THAT(report.failures[1], HasSubstr("rsp.gripper_valve: writing its safe level (active) failed"));
}

// --- the whole of --safe-outputs on the simulation board (fake backend) ----------------------

TEST(RunSafeOutputs, OnTheSimulationBoardDrivesTheRspValvesAndExitsZero) {
  std::ostringstream text;
  spdlog::logger log("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(text));
  const int code = run_safe_outputs({source("boards/host-sim.yaml"), source("hubs/rsp_ecu/rsp_ecu.yaml"),
                                     assembly::BackendKind::kFake, &assembly::fake_simulation()},
                                    log);
  EXPECT_EQ(code, kSafeOutputsDone) << text.str();
  EXPECT_THAT(text.str(), HasSubstr("rsp.lock_valve: driven to its safe level (inactive)"));
  EXPECT_THAT(text.str(), HasSubstr("all 2 outputs driven to their safe levels"));
}

TEST(RunSafeOutputs, NamesTheBusesOfTheToolEcuAsNotTouched) {
  std::ostringstream text;
  spdlog::logger log("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(text));
  const int code = run_safe_outputs({source("boards/host-sim.yaml"), source("hubs/tool_ecu/tool_ecu.yaml"),
                                     assembly::BackendKind::kFake, &assembly::fake_simulation()},
                                    log);
  EXPECT_EQ(code, kSafeOutputsDone) << text.str();
  EXPECT_THAT(text.str(), HasSubstr("lift_drive (Modbus): simulated inside the stopped hubd"));
  EXPECT_THAT(text.str(), HasSubstr("tool_bus (CAN): not touched"));
  EXPECT_THAT(text.str(), HasSubstr("tool.run_forward: driven to its safe level (inactive)"));
}

TEST(RunSafeOutputs, ABrokenOrMismatchedConfigurationExitsTwo) {
  std::ostringstream text;
  spdlog::logger log("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(text));
  EXPECT_EQ(run_safe_outputs({source("boards/rpi4-dock-ecu.yaml"), source("hubs/rsp_ecu/rsp_ecu.yaml"),
                              assembly::BackendKind::kLinux},
                             log),
            kSafeOutputsConfigError);
  EXPECT_EQ(run_safe_outputs({source("boards/no-such-board.yaml"), source("hubs/rsp_ecu/rsp_ecu.yaml"),
                              assembly::BackendKind::kLinux},
                             log),
            kSafeOutputsConfigError);
}

TEST(RunSafeOutputs, OnAMachineWithoutTheChipEveryOutputIsNamedAndItExitsOne) {
  auto chips = hal::list_gpio_chips();
  ASSERT_TRUE(chips) << chips.error().message;
  for (const hal::GpioChipInfo& chip : *chips) {
    if (chip.label == "pinctrl-bcm2711")
      GTEST_SKIP() << "this is a Raspberry Pi 4: its lines would be driven";
  }
  std::ostringstream text;
  spdlog::logger log("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(text));
  const int code = run_safe_outputs({source("boards/rpi4-rsp-ecu.yaml"), source("hubs/rsp_ecu/rsp_ecu.yaml"),
                                     assembly::BackendKind::kLinux},
                                    log);
  EXPECT_EQ(code, kSafeOutputsFailed) << text.str();
  EXPECT_THAT(text.str(), HasSubstr("2 of 2 outputs NOT driven safe: rsp.lock_valve, rsp.gripper_valve"));
}

}  // namespace
}  // namespace hubrt::hubd
