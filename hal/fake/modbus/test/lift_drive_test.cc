// The lift drive model against docs/protocols/lift-drive-modbus.md, with a ManualClock.
#include "hubrt/hal/fake/lift_drive.h"

#include <array>
#include <vector>

#include <gtest/gtest.h>

namespace hubrt::hal::fake {
namespace {

namespace ld = protocol::lift_drive;
using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::uint16_t kEnableMove = ld::control::kEnable | ld::control::kMove;

class LiftDriveTest : public ::testing::Test {
 protected:
  ModbusException write(std::uint16_t reg, std::uint16_t value) {
    return drive.write_holding(reg, std::span<const std::uint16_t>(&value, 1), now());
  }
  ModbusException write_all(std::uint16_t first, std::vector<std::uint16_t> values) {
    return drive.write_holding(first, values, now());
  }
  void control(std::uint16_t word) {
    ASSERT_EQ(write(ld::holding::kControlWord, word), ModbusException::kNone);
  }
  LiftDriveRegisters read() { return drive.read(now()); }
  std::uint16_t position() { return read().input[ld::input::kActualPosition]; }
  std::uint16_t status() { return read().status_word(); }
  std::uint16_t fault() { return read().input[ld::input::kFaultCode]; }
  auto speed() { return static_cast<std::int16_t>(read().input[ld::input::kActualSpeed]); }
  Time now() const { return clock.now().mono; }

  ManualClock clock;
  LiftDrive drive{LiftDriveConfig{}, clock.now().mono};
};

TEST_F(LiftDriveTest, PowersUpDisabledInPositionAtTheBottom) {
  const LiftDriveRegisters r = read();
  EXPECT_EQ(r.input[ld::input::kActualPosition], 0);
  EXPECT_EQ(r.status_word(), ld::status::kInPosition | ld::status::kLimitDown);
  EXPECT_EQ(r.holding[ld::holding::kSpeed], 50);
  EXPECT_EQ(r.holding[ld::holding::kTargetPosition], 0);
  EXPECT_EQ(r.input[ld::input::kFaultCode], 0);
}

TEST_F(LiftDriveTest, MovesAtItsSpeedAndReportsInPosition) {
  ASSERT_EQ(write(ld::holding::kTargetPosition, 1000), ModbusException::kNone);  // 100.0 mm
  control(kEnableMove);
  EXPECT_EQ(status() & (ld::status::kEnabled | ld::status::kMoving),
            ld::status::kEnabled | ld::status::kMoving);

  clock.advance(seconds(1));
  EXPECT_EQ(position(), 500) << "50 mm/s for 1 s";
  EXPECT_EQ(speed(), 50);
  EXPECT_EQ(status() & ld::status::kInPosition, 0);
  EXPECT_EQ(status() & ld::status::kLimitDown, 0);

  clock.advance(milliseconds(999));
  EXPECT_EQ(status() & ld::status::kInPosition, 0) << "not yet there";
  clock.advance(milliseconds(1));
  EXPECT_EQ(position(), 1000);
  EXPECT_EQ(status(), ld::status::kEnabled | ld::status::kInPosition);
  EXPECT_EQ(speed(), 0);

  ASSERT_EQ(write(ld::holding::kTargetPosition, 800), ModbusException::kNone);
  EXPECT_EQ(speed(), -50) << "downwards is negative";
  clock.advance(milliseconds(200));
  EXPECT_EQ(position(), 900);
}

TEST_F(LiftDriveTest, SpeedAndTargetChangesTakeEffectOnTheFly) {
  ASSERT_EQ(write_all(ld::holding::kTargetPosition, {4000, 200}), ModbusException::kNone);
  control(kEnableMove);
  clock.advance(milliseconds(500));
  EXPECT_EQ(position(), 1000);
  ASSERT_EQ(write(ld::holding::kSpeed, 100), ModbusException::kNone);
  clock.advance(milliseconds(500));
  EXPECT_EQ(position(), 1500);
}

TEST_F(LiftDriveTest, LimitSwitchesAtBothEndsOfTravel) {
  ASSERT_EQ(write_all(ld::holding::kTargetPosition, {4000, 200}), ModbusException::kNone);
  control(kEnableMove);
  clock.advance(seconds(2));
  EXPECT_EQ(position(), 4000);
  EXPECT_EQ(status() & (ld::status::kLimitUp | ld::status::kLimitDown), ld::status::kLimitUp);
  ASSERT_EQ(write(ld::holding::kTargetPosition, 0), ModbusException::kNone);
  clock.advance(seconds(2));
  EXPECT_EQ(status() & (ld::status::kLimitUp | ld::status::kLimitDown), ld::status::kLimitDown);
}

TEST_F(LiftDriveTest, StopAndMoveOffHoldPosition) {
  ASSERT_EQ(write(ld::holding::kTargetPosition, 1000), ModbusException::kNone);
  control(kEnableMove);
  clock.advance(milliseconds(400));
  control(kEnableMove | ld::control::kStop);
  clock.advance(seconds(1));
  EXPECT_EQ(position(), 200) << "stop overrides move";
  EXPECT_EQ(status() & (ld::status::kMoving | ld::status::kInPosition), 0);
  control(ld::control::kEnable);
  clock.advance(seconds(1));
  EXPECT_EQ(position(), 200) << "move off holds too";
  control(kEnableMove);
  clock.advance(milliseconds(400));
  EXPECT_EQ(position(), 400) << "and motion resumes";
}

TEST_F(LiftDriveTest, OvercurrentTripsAndNeedsResetAndAFreshEnableEdge) {
  ASSERT_EQ(write(ld::holding::kTargetPosition, 1000), ModbusException::kNone);
  control(kEnableMove);
  clock.advance(milliseconds(200));
  drive.inject_overcurrent(now());
  EXPECT_EQ(fault(), static_cast<std::uint16_t>(ld::FaultCode::kOvercurrent));
  EXPECT_EQ(status(), ld::status::kFault);
  clock.advance(seconds(1));
  EXPECT_EQ(position(), 100) << "a faulted drive does not move";

  control(kEnableMove);  // repeated by a state-based master: changes nothing
  EXPECT_TRUE(status() & ld::status::kFault);
  control(kEnableMove | ld::control::kResetFault);
  EXPECT_EQ(fault(), 0);
  EXPECT_EQ(status() & ld::status::kEnabled, 0) << "reset alone does not power the stage";
  control(ld::control::kMove);
  control(kEnableMove);
  EXPECT_TRUE(status() & ld::status::kEnabled);
  clock.advance(milliseconds(200));
  EXPECT_EQ(position(), 200);
}

TEST_F(LiftDriveTest, JammedLoadTripsAFollowingError) {
  drive.set_blocked(true, now());
  ASSERT_EQ(write(ld::holding::kTargetPosition, 1000), ModbusException::kNone);
  control(kEnableMove);
  // 5 mm of lag at 50 mm/s: 100 ms.
  clock.advance(milliseconds(99));
  EXPECT_EQ(fault(), 0);
  EXPECT_EQ(speed(), 0) << "commanded, but nothing moves";
  clock.advance(milliseconds(2));
  EXPECT_EQ(fault(), static_cast<std::uint16_t>(ld::FaultCode::kFollowingError));
  EXPECT_EQ(position(), 0);

  drive.set_blocked(false, now());
  control(ld::control::kResetFault);
  control(kEnableMove);
  clock.advance(milliseconds(100));
  EXPECT_EQ(position(), 50);
}

TEST_F(LiftDriveTest, OvertemperatureCannotBeResetWhileHot) {
  drive.set_overtemperature(true, now());
  EXPECT_EQ(fault(), static_cast<std::uint16_t>(ld::FaultCode::kOvertemperature));
  control(ld::control::kResetFault);
  EXPECT_EQ(fault(), static_cast<std::uint16_t>(ld::FaultCode::kOvertemperature)) << "the cause persists";
  drive.set_overtemperature(false, now());
  control(0);
  control(ld::control::kResetFault);
  EXPECT_EQ(fault(), 0);
}

TEST_F(LiftDriveTest, WatchdogTripsWhenTheMasterFallsSilent) {
  ASSERT_EQ(write_all(ld::holding::kTargetPosition, {4000, 100, 200}), ModbusException::kNone);
  control(kEnableMove);
  clock.advance(milliseconds(150));
  EXPECT_EQ(fault(), 0) << "a read feeds the watchdog";
  clock.advance(milliseconds(200));
  EXPECT_EQ(fault(), 0) << "exactly at the limit is still in time";
  clock.advance(milliseconds(500));
  const LiftDriveRegisters r = read();
  EXPECT_EQ(r.input[ld::input::kFaultCode], static_cast<std::uint16_t>(ld::FaultCode::kWatchdog));
  // Moved 350 ms + 200 ms until the watchdog expired, at 100 mm/s.
  EXPECT_EQ(r.input[ld::input::kActualPosition], 550);
}

TEST_F(LiftDriveTest, InvalidWritesAreRefusedWhole) {
  EXPECT_EQ(write(ld::holding::kTargetPosition, 4001), ModbusException::kIllegalDataValue);
  EXPECT_EQ(write(ld::holding::kSpeed, 0), ModbusException::kIllegalDataValue);
  EXPECT_EQ(write(ld::holding::kSpeed, 201), ModbusException::kIllegalDataValue);
  EXPECT_EQ(write(ld::holding::kWatchdogMs, 60001), ModbusException::kIllegalDataValue);
  EXPECT_EQ(write(ld::holding::kControlWord, 0x0010), ModbusException::kIllegalDataValue);
  EXPECT_EQ(write_all(ld::holding::kTargetPosition, {1000, 0}), ModbusException::kIllegalDataValue);
  EXPECT_EQ(read().holding[ld::holding::kTargetPosition], 0) << "all or nothing";
  EXPECT_EQ(write(ld::holding::kCount, 1), ModbusException::kIllegalDataAddress);
  EXPECT_EQ(write_all(ld::holding::kWatchdogMs, {1, 1}), ModbusException::kIllegalDataAddress);
}

TEST_F(LiftDriveTest, CoilsAreTheControlWordBits) {
  const std::array<bool, 2> enable_move{true, true};
  ASSERT_EQ(drive.write_coils(0, enable_move, now()), ModbusException::kNone);
  EXPECT_EQ(read().control_word(), kEnableMove);
  EXPECT_TRUE(status() & ld::status::kEnabled);
  const std::array<bool, 1> stop{true};
  ASSERT_EQ(drive.write_coils(2, stop, now()), ModbusException::kNone);
  EXPECT_EQ(read().control_word(), kEnableMove | ld::control::kStop);
  const std::array<bool, 2> beyond{true, true};
  EXPECT_EQ(drive.write_coils(3, beyond, now()), ModbusException::kIllegalDataAddress);
}

}  // namespace
}  // namespace hubrt::hal::fake
