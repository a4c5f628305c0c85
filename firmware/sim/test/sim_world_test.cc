// What /sim/input and /sim/fault do to the simulated station of boards/host-sim.yaml: each
// request reaches the simulator it names, and a wrong request is refused with a reason.
#include "hubrt/sim/sim_world.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"
#include "hubrt/protocol/lift_drive_modbus.h"
#include "hubrt/protocol/smart_tool_can.h"

namespace hubrt::sim {
namespace {

using std::chrono::milliseconds;
using ::testing::HasSubstr;

class SimWorldTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board.is_ok()) << board.error().message;
    board_ = std::move(*board);
    auto backend = hal::fake::FakeBackend::create(board_, clock_);
    ASSERT_TRUE(backend.is_ok()) << backend.error().message;
    fake_ = std::move(*backend);
  }

  Expected<void> fault(std::string_view device, std::string_view what, std::uint32_t value = 0) {
    return apply_fault(*fake_, board_, FaultRequest{device, what, value}, clock_.now().mono);
  }
  bool active(std::string_view signal) {
    const Result<bool> level = fake_->active(signal);
    EXPECT_TRUE(level.is_ok()) << signal;
    return level.value_or(false);
  }

  ManualClock clock_;
  hal::BoardConfig board_;
  std::unique_ptr<hal::fake::FakeBackend> fake_;
};

TEST_F(SimWorldTest, InputsReachDockSensorsPlainInputsAndPressureSupplies) {
  ASSERT_FALSE(active("dock.slot.smart_tool"));
  ASSERT_TRUE(apply_input(*fake_, "dock.slot.smart_tool", true));
  clock_.advance(milliseconds(100));  // past the sensor's bounce
  EXPECT_TRUE(active("dock.slot.smart_tool"));

  ASSERT_TRUE(apply_input(*fake_, "rsp.tool_id.filter_tool", true));
  EXPECT_TRUE(active("rsp.tool_id.filter_tool"));

  ASSERT_TRUE(active("rsp.pressure_ok"));
  ASSERT_TRUE(apply_input(*fake_, "main_air", false));
  EXPECT_FALSE(active("rsp.pressure_ok"));
  EXPECT_FALSE(fake_->pressure_supply("main_air")->ok());
}

TEST_F(SimWorldTest, AnOutputOrAnUnknownSignalIsNotAnInput) {
  auto refused = apply_input(*fake_, "rsp.lock_valve", true);
  ASSERT_FALSE(refused);
  EXPECT_EQ(refused.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(refused.error().message, HasSubstr("'rsp.lock_valve' is not a simulated input"));
  EXPECT_FALSE(apply_input(*fake_, "no.such.signal", true));
}

TEST_F(SimWorldTest, SmartToolFaultsReachTheControllerOnItsBus) {
  auto* tool = fake_->smart_tool("tool_bus");
  ASSERT_NE(tool, nullptr);
  ASSERT_TRUE(tool->snapshot().powered);
  ASSERT_TRUE(fault("tool_bus", "power_off"));
  EXPECT_FALSE(tool->snapshot().powered);
  ASSERT_TRUE(fault("tool_bus", "power_on"));
  EXPECT_TRUE(tool->snapshot().powered);

  ASSERT_TRUE(fault("tool_bus", "alarm"));  // no bits given: overcurrent
  EXPECT_EQ(tool->snapshot().alarms, protocol::smart_tool::alarm_bit::kOvercurrent);
  ASSERT_TRUE(fault("tool_bus", "alarm", protocol::smart_tool::alarm_bit::kTransducerFault));
  EXPECT_EQ(tool->snapshot().alarms, protocol::smart_tool::alarm_bit::kOvercurrent |
                                         protocol::smart_tool::alarm_bit::kTransducerFault);

  ASSERT_TRUE(fault("tool_bus", "bus_off"));
  EXPECT_FALSE(tool->snapshot().link_up);
  ASSERT_TRUE(fault("tool_bus", "bus_on"));
  EXPECT_TRUE(tool->snapshot().link_up);
}

TEST_F(SimWorldTest, LiftDriveFaultsReachTheDriveAndItsServer) {
  auto* drive = fake_->lift_drive("lift_drive");
  auto* server = fake_->lift_drive_server("lift_drive");
  ASSERT_NE(drive, nullptr);
  ASSERT_NE(server, nullptr);
  namespace ld = protocol::lift_drive;
  ASSERT_TRUE(fault("lift_drive", "overcurrent"));
  const auto registers = drive->read(clock_.now().mono);
  EXPECT_NE(registers.status_word() & ld::status::kFault, 0);
  EXPECT_EQ(registers.input[ld::input::kFaultCode], static_cast<std::uint16_t>(ld::FaultCode::kOvercurrent));

  ASSERT_TRUE(fault("lift_drive", "go_down"));
  EXPECT_FALSE(server->is_up());
  ASSERT_TRUE(fault("lift_drive", "come_back"));
  EXPECT_TRUE(server->is_up());
  ASSERT_TRUE(fault("lift_drive", "stop_answering"));
  ASSERT_TRUE(fault("lift_drive", "answer"));
}

TEST_F(SimWorldTest, ValveAndSupplyFaults) {
  // Nobody drives the gripper valve here: the gripper is open, both confirms off.
  ASSERT_FALSE(active("rsp.gripper.confirm_a"));
  ASSERT_FALSE(active("rsp.gripper.confirm_b"));
  ASSERT_TRUE(fault("rsp.gripper_valve", "fail_confirm", 1));
  EXPECT_FALSE(active("rsp.gripper.confirm_a"));
  EXPECT_TRUE(active("rsp.gripper.confirm_b")) << "a failed sensor reads active whatever the gripper does";
  ASSERT_TRUE(fault("rsp.gripper_valve", "repair_confirm", 1));
  EXPECT_FALSE(active("rsp.gripper.confirm_b"));

  ASSERT_TRUE(fault("main_air", "drop"));
  EXPECT_FALSE(active("rsp.pressure_ok"));
  ASSERT_TRUE(fault("main_air", "restore"));
  EXPECT_TRUE(active("rsp.pressure_ok"));

  auto out_of_range = fault("rsp.gripper_valve", "fail_confirm", 2);
  ASSERT_FALSE(out_of_range);
  EXPECT_THAT(out_of_range.error().message, HasSubstr("has 2 confirm sensor(s); there is no index 2"));
  ASSERT_TRUE(fault("rsp.lock_valve", "stick"));
  ASSERT_TRUE(fault("rsp.lock_valve", "unstick"));
}

TEST_F(SimWorldTest, AFaultADeviceDoesNotHaveIsRefusedWithTheFaultsItHas) {
  auto wrong = fault("lift_drive", "power_off");
  ASSERT_FALSE(wrong);
  EXPECT_EQ(wrong.error().code, ErrorCode::kInvalidArgument);
  EXPECT_THAT(wrong.error().message,
              HasSubstr("lift drive 'lift_drive' has no fault 'power_off' (it has: overcurrent"));
  auto unknown = fault("conveyor", "stop");
  ASSERT_FALSE(unknown);
  EXPECT_EQ(unknown.error().code, ErrorCode::kNotFound);
  EXPECT_THAT(unknown.error().message, HasSubstr("'conveyor' is not a simulated device"));
}

}  // namespace
}  // namespace hubrt::sim
