// The fake backend built from boards/host-sim.yaml: devices opened through the Backend interface
// behave like the station's devices, and the hooks reach the simulators behind them.
#include "hubrt/hal/fake/fake_backend.h"

#include <array>
#include <optional>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"
#include "hubrt/protocol/lift_drive_modbus.h"
#include "hubrt/protocol/smart_tool_can.h"

namespace hubrt::hal::fake {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

class FakeBackendTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board.is_ok()) << board.error().message;
    board_ = std::move(*board);
    auto backend = FakeBackend::create(board_, clock_);
    ASSERT_TRUE(backend.is_ok()) << backend.error().message;
    backend_ = std::move(*backend);
  }

  std::unique_ptr<DigitalInput> input(std::string_view signal) {
    const BoardInput* declared = board_.find_input(signal);
    EXPECT_NE(declared, nullptr) << signal;
    if (declared == nullptr) return nullptr;
    auto opened = backend_->open_input(declared->config);
    EXPECT_TRUE(opened.is_ok()) << opened.error().message;
    return opened ? std::move(*opened) : nullptr;
  }
  std::unique_ptr<DigitalOutput> output(std::string_view signal) {
    const BoardOutput* declared = board_.find_output(signal);
    EXPECT_NE(declared, nullptr) << signal;
    if (declared == nullptr) return nullptr;
    auto opened = backend_->open_output(declared->config);
    EXPECT_TRUE(opened.is_ok()) << opened.error().message;
    return opened ? std::move(*opened) : nullptr;
  }
  bool read(DigitalInput& in) {
    const Result<bool> level = in.read(clock_.now().mono);
    EXPECT_TRUE(level.is_ok());
    return level.value_or(false);
  }
  // Reads every millisecond for `span`; returns when the input first read `level`, or nothing.
  std::optional<Duration> time_until(DigitalInput& in, bool level, Duration span) {
    const Time start = clock_.now().mono;
    for (Duration t{0}; t <= span; t += milliseconds(1)) {
      if (read(in) == level) return clock_.now().mono - start;
      clock_.advance(milliseconds(1));
    }
    return std::nullopt;
  }

  ManualClock clock_;
  BoardConfig board_;
  std::unique_ptr<FakeBackend> backend_;
};

TEST_F(FakeBackendTest, StartsInTheStateTheBoardDescribes) {
  auto ladder_frame = input("dock.slot.ladder_frame_tool");
  auto smart_tool_home = input("dock.slot.smart_tool");
  auto holds_smart_tool = input("rsp.tool_id.smart_tool");
  auto holds_filter_tool = input("rsp.tool_id.filter_tool");
  auto arm_home = input("tool.arm.home");
  auto pressure = input("rsp.pressure_ok");
  auto button = input("tool.button.forward");
  EXPECT_TRUE(read(*ladder_frame));
  EXPECT_FALSE(read(*smart_tool_home));
  EXPECT_TRUE(read(*holds_smart_tool));
  EXPECT_FALSE(read(*holds_filter_tool));
  EXPECT_TRUE(read(*arm_home));
  EXPECT_TRUE(read(*pressure));
  EXPECT_FALSE(read(*button));
  // The button is active low: released means the line is pulled high.
  const auto wiring = backend_->wiring("tool.button.forward");
  ASSERT_TRUE(wiring.is_ok());
  EXPECT_TRUE(wiring.value().chip->level(wiring.value().line).value());
}

TEST_F(FakeBackendTest, GripperConfirmsFollowTheValveThroughDebouncing) {
  auto confirm_a = input("rsp.gripper.confirm_a");
  auto confirm_b = input("rsp.gripper.confirm_b");
  EXPECT_FALSE(read(*confirm_a));
  auto gripper = output("rsp.gripper_valve");  // initial: true (grip) → the valve strokes
  // 150 ms actuation, then 10 ms debounce.
  EXPECT_EQ(time_until(*confirm_a, true, milliseconds(500)), milliseconds(160));
  EXPECT_TRUE(read(*confirm_b));
  ASSERT_TRUE(gripper->write(false).is_ok());
  EXPECT_EQ(time_until(*confirm_b, false, milliseconds(500)), milliseconds(160));
}

TEST_F(FakeBackendTest, PressureDropStopsTheValveAndShowsOnTheSwitch) {
  auto pressure = input("rsp.pressure_ok");
  auto confirm = input("rsp.gripper.confirm_a");
  auto lock = output("rsp.lock_valve");
  auto gripper = output("rsp.gripper_valve");
  ASSERT_NE(backend_->pressure_supply("main_air"), nullptr);
  EXPECT_TRUE(read(*pressure));  // the first read is reported as it is: nothing to debounce against
  backend_->pressure_supply("main_air")->drop();
  EXPECT_EQ(time_until(*pressure, false, milliseconds(200)), milliseconds(50));  // 50 ms debounce
  clock_.advance(milliseconds(500));
  EXPECT_FALSE(read(*confirm));  // no air, no stroke
  EXPECT_FALSE(backend_->valve("rsp.gripper_valve")->in_energised_position());
  backend_->pressure_supply("main_air")->restore();
  EXPECT_EQ(time_until(*confirm, true, milliseconds(500)), milliseconds(160));
}

TEST_F(FakeBackendTest, DockingBouncesAndTheDebouncedInputReportsOnce) {
  auto slot = input("dock.slot.smart_tool");
  ASSERT_NE(backend_->dock_sensor("dock.slot.smart_tool"), nullptr);
  EXPECT_FALSE(read(*slot));
  backend_->dock_sensor("dock.slot.smart_tool")->set_occupied(true);
  // Bounces for 15 ms, then the 20 ms debounce: reported at 35 ms and never falls back.
  EXPECT_EQ(time_until(*slot, true, milliseconds(100)), milliseconds(35));
  for (int i = 0; i < 50; ++i) {
    clock_.advance(milliseconds(1));
    EXPECT_TRUE(read(*slot));
  }
}

TEST_F(FakeBackendTest, OutputsAreObservedWithTheirTimes) {
  const Time t0 = clock_.now().mono;
  auto forward = output("tool.run_forward");
  clock_.advance(milliseconds(30));
  ASSERT_TRUE(forward->write(true).is_ok());
  clock_.advance(milliseconds(70));
  ASSERT_TRUE(forward->write_safe().is_ok());
  EXPECT_THAT(backend_->history("tool.run_forward"),
              ElementsAre(FakeBackend::SignalChange{t0, false},
                          FakeBackend::SignalChange{t0 + milliseconds(30), true},
                          FakeBackend::SignalChange{t0 + milliseconds(100), false}));
  EXPECT_FALSE(backend_->active("tool.run_forward").value());
  EXPECT_EQ(backend_->active("no.such.signal").status().code(), ErrorCode::kNotFound);
}

TEST_F(FakeBackendTest, PlainInputsAreSetThroughTheirHooks) {
  auto button = input("tool.button.reverse");
  ASSERT_NE(backend_->input("tool.button.reverse"), nullptr);
  EXPECT_EQ(backend_->input("rsp.pressure_ok"), nullptr);  // driven by the supply, not settable
  EXPECT_FALSE(read(*button));
  backend_->input("tool.button.reverse")->set(true);
  EXPECT_EQ(time_until(*button, true, milliseconds(100)), milliseconds(20));
}

TEST_F(FakeBackendTest, TheSmartToolControllerIsOnTheVirtualBus) {
  const BoardCanBus* bus = board_.find_can("tool_bus");
  ASSERT_NE(bus, nullptr);
  auto can = backend_->open_can(bus->config);
  ASSERT_TRUE(can.is_ok()) << can.error().message;
  ASSERT_NE(backend_->smart_tool("tool_bus"), nullptr);
  clock_.advance(protocol::smart_tool::kHeartbeatPeriod);
  bool heartbeat = false;
  for (int i = 0; i < 16 && !heartbeat; ++i) {
    const Result<CanFrame> frame = (*can)->receive(Duration::zero());
    if (!frame.is_ok()) break;
    heartbeat = frame.value().id == protocol::smart_tool::frame_id(protocol::smart_tool::Function::kHeartbeat,
                                                                   protocol::smart_tool::kDefaultNodeId);
  }
  EXPECT_TRUE(heartbeat);
}

TEST_F(FakeBackendTest, TheLiftDriveAnswersTheRealModbusClientOnLoopback) {
  const BoardModbusDevice* device = board_.find_modbus("lift_drive");
  ASSERT_NE(device, nullptr);
  ModbusConfig config = device->config;
  // Real sockets: a generous timeout, as sanitizer builds on this busy 2-core machine are slow.
  config.response_timeout = std::chrono::seconds(2);
  auto client = backend_->open_modbus(config);
  ASSERT_TRUE(client.is_ok()) << client.error().message;
  std::array<std::uint16_t, protocol::lift_drive::input::kCount> registers{};
  const Status read_status = (*client)->read_input_registers(0, registers);
  ASSERT_TRUE(read_status.is_ok()) << to_string(read_status.code());
  EXPECT_EQ(registers[protocol::lift_drive::input::kFaultCode], 0);
  ASSERT_NE(backend_->lift_drive_server("lift_drive"), nullptr);
  EXPECT_NE(backend_->lift_drive_server("lift_drive")->port(), 0);
  EXPECT_GE(backend_->lift_drive_server("lift_drive")->requests_answered(), 1U);
}

TEST_F(FakeBackendTest, AModbusDeviceWithoutSimulatorIsNotFound) {
  ModbusConfig config;
  config.device = "pump";
  auto client = backend_->open_modbus(config);
  ASSERT_FALSE(client.is_ok());
  EXPECT_EQ(client.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(client.error().message, HasSubstr("pump"));
}

TEST(FakeBackendCreate, RefusesABoardWithoutSimulation) {
  auto board = load_board(std::string(HUBRT_BOARDS_DIR) + "/rpi4-dock-ecu.yaml");
  ASSERT_TRUE(board.is_ok()) << board.error().message;
  ManualClock clock;
  auto backend = FakeBackend::create(*board, clock);
  ASSERT_FALSE(backend.is_ok());
  EXPECT_EQ(backend.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(backend.error().message, HasSubstr("has no simulation section"));
}

}  // namespace
}  // namespace hubrt::hal::fake
