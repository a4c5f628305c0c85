// The lift node's behaviour (lift_logic_fixture.h: the manual clock, a scripted asynchronous
// Modbus device in front of the drive model). The HAL's threaded implementation against the real
// libmodbus server is tested in hal/common/test/threaded_async_modbus_test.cc; how the logic meets
// the asynchronous device in lift_logic_async_test.cc.
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "lift_logic_fixture.h"
#include "reading_age.h"

namespace hubrt::tool_ecu::testing {
namespace {

TEST_F(LiftLogicTest, MovesToANamedPositionAndReportsIt) {
  start();
  const Order work = move("work");
  step(&work);  // the first request reads the drive
  EXPECT_FALSE(state_.drive_online()) << "no reading yet";
  step(&work);
  EXPECT_TRUE(state_.drive_online());
  EXPECT_EQ(state_.target(), "work");
  EXPECT_FLOAT_EQ(state_.target_mm(), 120.0F);
  ASSERT_TRUE(step_until(&work, [&] { return state_.moving(); })) << errors();
  EXPECT_TRUE(state_.enabled());
  EXPECT_FLOAT_EQ(state_.speed_mm_s(), 100.0F) << "the hub file's speed, up";
  EXPECT_EQ(state_.at(), "");
  ASSERT_TRUE(step_until(&work, [&] { return std::string(state_.at()) == "work"; })) << errors();
  EXPECT_TRUE(state_.in_position());
  EXPECT_FALSE(state_.moving());
  EXPECT_NEAR(state_.position_mm(), 120.0, 0.5);
  EXPECT_NEAR(drive_.position_mm(clock_.now().mono), 120.0, 0.5);
  EXPECT_TRUE(errors_.empty()) << errors();

  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return std::string(state_.at()) == "home"; })) << errors();
  EXPECT_NEAR(state_.position_mm(), 380.0, 0.5);
  const Order floating = move("float");
  ASSERT_TRUE(step_until(&floating, [&] { return state_.moving(); }));
  EXPECT_FLOAT_EQ(state_.speed_mm_s(), -100.0F) << "down";
  ASSERT_TRUE(step_until(&floating, [&] { return std::string(state_.at()) == "float"; }));
  EXPECT_NEAR(state_.position_mm(), 250.0, 0.5);
}

TEST_F(LiftLogicTest, TheDriveGetsItsSpeedAndWatchdogFromTheHubFile) {
  start();
  const Order stop = action("stop");
  step(&stop);  // reads the drive
  step(&stop);  // the reading came back: writes
  step(&stop);
  const auto registers = drive_.read(clock_.now().mono);
  EXPECT_EQ(registers.holding[ld::holding::kSpeed], 100);
  EXPECT_EQ(registers.holding[ld::holding::kWatchdogMs], 1000);
  EXPECT_EQ(registers.control_word(), ld::control::kStop) << "stop never switches the power stage on";
  EXPECT_FALSE(state_.enabled());
}

TEST_F(LiftLogicTest, StopHaltsAndHolds) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.position_mm() > 50.0F; }));
  const Order stop = action("stop");
  step(&stop);
  step(&stop);
  const float held = state_.position_mm();
  steps(stop, 5);
  EXPECT_FLOAT_EQ(state_.position_mm(), held);
  EXPECT_FALSE(state_.moving());
  EXPECT_EQ(state_.target(), "");
  EXPECT_NE(drive_control_word() & ld::control::kStop, 0);
}

TEST_F(LiftLogicTest, NoCommandInForceStopsTheLift) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.position_mm() > 50.0F; }));
  step(nullptr);
  step(nullptr);
  const float held = state_.position_mm();
  for (int i = 0; i < 5; ++i) step(nullptr);
  EXPECT_FLOAT_EQ(state_.position_mm(), held);
  EXPECT_FALSE(state_.moving());
}

TEST_F(LiftLogicTest, EnterSafeStateAndShutdownStopTheDrive) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  // The drive answered the request in flight; safe state comes before the next cycle and sends
  // "stop" at once, without waiting for a cycle.
  ASSERT_TRUE(script_.complete(clock_.now().mono));
  const std::size_t before = script_.submitted().size();
  logic_->enter_safe_state();
  ASSERT_EQ(script_.submitted().size(), before + 1);
  EXPECT_EQ(submitted_control_word(), ld::control::kStop | ld::control::kEnable) << "halt and hold";
  ASSERT_TRUE(script_.complete(clock_.now().mono));
  EXPECT_NE(drive_control_word() & ld::control::kStop, 0);

  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  EXPECT_EQ(drive_control_word() & ld::control::kStop, 0);
  // "Stop" is the device's write-on-close: the last word even with a move request in flight.
  EXPECT_EQ(script_.write_on_close(),
            (std::vector<std::uint16_t>{ld::control::kStop | ld::control::kEnable}));
  close();
  EXPECT_TRUE(script_.closed());
  EXPECT_NE(drive_control_word() & ld::control::kStop, 0);
  EXPECT_FALSE(drive_.read(clock_.now().mono).status_word() & ld::status::kMoving);
}

TEST_F(LiftLogicTest, ADriveFaultStopsLatchesAndNeedsResetAndAFreshMove) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  drive_.inject_overcurrent(clock_.now().mono);
  step(&home);
  EXPECT_TRUE(state_.fault());
  EXPECT_EQ(state_.fault_code(), 1);
  EXPECT_EQ(state_.fault_text(), "overcurrent");
  EXPECT_FALSE(state_.enabled());
  EXPECT_NE(errors().find("lift drive fault 1 (overcurrent); lift stopped; send reset to clear"),
            std::string::npos)
      << errors();
  EXPECT_EQ(logic_->condition(), runtime::NodeCondition::kFault) << "the node's lifecycle: fault";
  const float held = state_.position_mm();
  steps(home, 5);  // the planner keeps asking: nothing moves
  EXPECT_FLOAT_EQ(state_.position_mm(), held);

  reset_command();
  ASSERT_TRUE(step_until(
      &home, [&] { return !state_.fault(); }, 10))
      << "the reset pulse reached the drive";
  EXPECT_EQ(logic_->condition(), runtime::NodeCondition::kOk);
  // The reset command took effect; the planner's next move is fresh: the drive needs an enable edge.
  const Order floating = move("float");
  ASSERT_TRUE(step_until(&floating, [&] { return std::string(state_.at()) == "float"; })) << errors();
  EXPECT_TRUE(errors_.empty()) << errors();
}

TEST_F(LiftLogicTest, AJammedLoadTripsAFollowingErrorAndRecoversAfterReset) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  drive_.set_blocked(true, clock_.now().mono);
  ASSERT_TRUE(step_until(&home, [&] { return state_.fault(); }));
  EXPECT_EQ(state_.fault_code(), 2);
  EXPECT_EQ(state_.fault_text(), "following error");
  drive_.set_blocked(false, clock_.now().mono);
  steps(home, 3);
  EXPECT_TRUE(state_.fault()) << "latched in the drive until reset";
  reset_command();
  ASSERT_TRUE(step_until(&home, [&] { return std::string(state_.at()) == "home"; })) << errors();
}

TEST_F(LiftLogicTest, AnOvertemperatureCannotBeResetWhileHot) {
  start();
  const Order work = move("work");
  ASSERT_TRUE(step_until(&work, [&] { return state_.moving(); }));
  drive_.set_overtemperature(true, clock_.now().mono);
  ASSERT_TRUE(step_until(
      &work, [&] { return state_.fault(); }, 5));
  reset_command();
  steps(work, 3);
  EXPECT_EQ(state_.fault_code(), 3) << "refused while still hot";
  EXPECT_NE(errors().find("lift drive fault 3 (overtemperature)"), std::string::npos) << errors();
  drive_.set_overtemperature(false, clock_.now().mono);
  reset_command();
  ASSERT_TRUE(step_until(&work, [&] { return std::string(state_.at()) == "work"; })) << errors();
}

TEST_F(LiftLogicTest, ADriveThatStopsAnsweringIsAnErrorNotAHang) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  answering_ = false;
  step(&home);
  EXPECT_GT(logic_->snapshot().failures_in_a_row, 0u) << "the client's call timed out";
  EXPECT_EQ(logic_->snapshot().last_error, ErrorCode::kTimeout);
  steps(home, 5);  // 600 ms of manual time without an answer; the last reading's request 700 ms ago
  EXPECT_FALSE(state_.drive_online());
  EXPECT_NE(errors().find("not answering for 0.70 s"), std::string::npos) << errors();
  EXPECT_NE(errors().find("limit 0.50 s, last error: timeout); lift state unknown"), std::string::npos)
      << errors();

  answering_ = true;
  step(&home);
  EXPECT_TRUE(state_.drive_online());
  EXPECT_NE(errors().find("stopped answering for a while; send reset to clear"), std::string::npos)
      << errors();
  // That request only read the drive (nothing is written without a current reading); "stop" goes
  // out with the next one, decided from this reading.
  EXPECT_EQ(submitted_control_word(), ld::control::kStop | ld::control::kEnable);
  step(&home);
  const float held = state_.position_mm();
  steps(home, 3);
  EXPECT_FLOAT_EQ(state_.position_mm(), held) << "latched: no motion until reset";
  reset_command();
  EXPECT_TRUE(errors_.empty()) << errors();
  const Order work = move("work");
  ASSERT_TRUE(step_until(&work, [&] { return std::string(state_.at()) == "work"; })) << errors();
}

// The drive stops answering mid-move. Its last reading (moving up at 100 mm/s) holds for
// answer_within (500 ms); after that the State shows nothing of it as current, while the drive
// really does carry on until its own communication watchdog (1000 ms, from the hub file) stops it.
TEST_F(LiftLogicTest, AReadingOlderThanItsValidityIsUnknownUntilAFreshOneConfirmsTheLift) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving() && state_.position_mm() > 20.0F; }));
  answering_ = false;
  step(&home);
  ASSERT_GT(logic_->snapshot().failures_in_a_row, 0u);
  const Time last_read = logic_->snapshot().read_at;
  const float last_seen_mm = state_.position_mm();

  clock_.set(last_read + milliseconds(500));  // the reading's last valid moment
  cycle(&home);
  EXPECT_TRUE(state_.drive_online());
  EXPECT_EQ(state_.reading_age_ms(), 500u);
  EXPECT_TRUE(state_.moving()) << "still within its validity";

  clock_.set(last_read + milliseconds(501));
  cycle(&home);
  EXPECT_FALSE(state_.drive_online());
  EXPECT_EQ(state_.reading_age_ms(), 501u);
  EXPECT_FALSE(state_.moving()) << "never true from a stale reading";
  EXPECT_FALSE(state_.enabled());
  EXPECT_FALSE(state_.in_position());
  EXPECT_FALSE(state_.fault());
  EXPECT_EQ(state_.fault_code(), 0);
  EXPECT_EQ(state_.fault_text(), "unknown");
  EXPECT_EQ(state_.at(), "");
  EXPECT_TRUE(std::isnan(state_.position_mm())) << "not measured: NaN, not a position 0";
  EXPECT_TRUE(std::isnan(state_.speed_mm_s()));
  EXPECT_EQ(state_.target(), "home") << "the command's target is the hub's own, not a reading";
  EXPECT_EQ(errors().find("stopped"), std::string::npos) << "nobody knows it stopped: " << errors();
  EXPECT_NE(errors().find(fmt::format("lift motion unknown: last seen at {:.1f} mm, moving; the drive's own "
                                      "watchdog stops it 1000 ms after the last request it got",
                                      last_seen_mm)),
            std::string::npos)
      << errors();
  // Indeed the simulated drive moved on: 40 mm in the 400 ms since it was read (100 ms after the
  // request that read it went out).
  EXPECT_GT(drive_.position_mm(clock_.now().mono), last_seen_mm + 35.0);

  // Its watchdog trips 1000 ms after the last request it got (the last read, 100 ms after last_read).
  clock_.set(last_read + milliseconds(1200));
  cycle(&home);
  EXPECT_EQ(state_.reading_age_ms(), 1200u);
  EXPECT_FALSE(state_.moving());
  const auto drive = drive_.read(clock_.now().mono);
  EXPECT_EQ(drive.input[ld::input::kFaultCode], static_cast<std::uint16_t>(ld::FaultCode::kWatchdog));
  EXPECT_EQ(drive.input[ld::input::kStatusWord] & ld::status::kMoving, 0);

  // A fresh reading confirms it: stopped by its watchdog, values current again.
  answering_ = true;
  step(&home);
  EXPECT_TRUE(state_.drive_online());
  EXPECT_LE(state_.reading_age_ms(), 100u);
  EXPECT_FALSE(state_.moving());
  EXPECT_TRUE(state_.fault());
  EXPECT_EQ(state_.fault_code(), 4);
  EXPECT_EQ(state_.fault_text(), "communication watchdog");
  EXPECT_NEAR(state_.position_mm(), drive_.position_mm(clock_.now().mono), 0.15);  // register: 0.1 mm
  EXPECT_GT(state_.position_mm(), last_seen_mm + 80.0F) << "where the drive went on its own";
  EXPECT_EQ(errors().find("lift motion unknown"), std::string::npos) << errors();
  EXPECT_NE(errors().find("stopped answering for a while; send reset to clear"), std::string::npos)
      << errors();
}

TEST_F(LiftLogicTest, ADriveThatNeverAnswersIsReportedAfterTheLimit) {
  answering_ = false;
  start();
  const Order home = move("home");
  cycle(&home);
  steps(home, 4);
  EXPECT_EQ(logic_->snapshot().last_error, ErrorCode::kTimeout);
  EXPECT_TRUE(errors_.empty()) << "not yet (400 ms): " << errors();
  steps(home, 2);
  EXPECT_FALSE(state_.drive_online());
  EXPECT_EQ(state_.reading_age_ms(), kNeverRead);
  EXPECT_FALSE(state_.moving());
  EXPECT_EQ(state_.fault_text(), "unknown");
  EXPECT_NE(errors().find("no answer since start (last error: timeout); lift state unknown"),
            std::string::npos)
      << errors();
  // A drive that comes up after the hub is normal operation: not latched.
  answering_ = true;
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); })) << errors();
}

TEST_F(LiftLogicTest, BadMoveCommandsAreRejectedWithTheirReason) {
  start();
  runtime::Problem problem;
  hub_msgs::LiftCommand command;
  const Order up = move("attic");
  command = up.message();
  EXPECT_FALSE(logic_->validate(command, problem));
  EXPECT_EQ(problem.view(), "unknown position 'attic' (expected one of: home, float, work)");
  const Order empty = move("");
  command = empty.message();
  EXPECT_FALSE(logic_->validate(command, problem));
  EXPECT_EQ(problem.view(), "unknown position '' (expected one of: home, float, work)");
  Order stop = action("stop");
  stop.position = "attic";
  command = stop.message();
  EXPECT_TRUE(logic_->validate(command, problem)) << "stop ignores the position";
}

}  // namespace
}  // namespace hubrt::tool_ecu::testing
