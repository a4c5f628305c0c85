// The lift node on the manual clock in front of the lift drive model (hal/fake LiftDrive) through
// a scripted asynchronous Modbus device (scripted_async_modbus.h): a request the logic submits
// reaches the drive only when the test completes it, so everything here is deterministic and
// nothing waits in real time. The HAL's threaded implementation against the real libmodbus
// server is tested in hal/common/test/threaded_async_modbus_test.cc.
#include "lift_logic.h"

#include <chrono>
#include <optional>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/fake/lift_drive.h"
#include "hubrt/protocol/lift_drive_modbus.h"

#include "reading_age.h"
#include "scripted_async_modbus.h"

namespace hubrt::tool_ecu {
namespace {

namespace ld = protocol::lift_drive;
using std::chrono::milliseconds;
using testing::DriveScript;

constexpr auto kStep = milliseconds(100);  // manual time per cycle (the hub's 10 Hz); answer_within is 500 ms

struct Order {
  std::string action;
  std::string position;
  std::string target_name = "lift";
  std::string target_type = "lift";

  [[nodiscard]] LiftCommand wire() const {
    LiftCommand command{};
    command.target_type = const_cast<char*>(target_type.c_str());  // NOLINT: wire type wants char*
    command.target_name = const_cast<char*>(target_name.c_str());  // NOLINT
    command.action = const_cast<char*>(action.c_str());            // NOLINT
    command.position = const_cast<char*>(position.c_str());        // NOLINT
    return command;
  }
};

Order move(std::string position) {
  Order order;
  order.action = "move";
  order.position = std::move(position);
  return order;
}
Order action(std::string name) {
  Order order;
  order.action = std::move(name);
  return order;
}

class LiftLogicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/tool_ecu/tool_ecu.yaml");
    ASSERT_TRUE(config) << config.error().message;
    for (const auto& node : config->nodes) {
      if (node.type == LiftLogic::kType) {
        auto settings = parse_lift_settings(node);
        ASSERT_TRUE(settings) << settings.error().message;
        settings_ = std::move(*settings);
      }
    }
  }
  void TearDown() override { close(); }

  void start() {
    auto logic = LiftLogic::create(settings_, script_.open(), clock_.now().mono);
    ASSERT_TRUE(logic) << logic.error().message;
    logic_.emplace(std::move(*logic));
  }
  // Destroys the logic, and with it the device: its write-on-close reaches the drive now.
  void close() {
    script_.set_close_time(clock_.now().mono);
    logic_.reset();
  }

  // One cycle at the current manual time, as the Node runs it.
  void cycle(const Order* order) {
    const Time now = clock_.now().mono;
    if (order != nullptr) command_ = order->wire();
    logic_->read_inputs(now);
    logic_->update(order == nullptr ? nullptr : &command_, now);
    errors_.clear();
    state_ = LiftState{};
    logic_->report(state_, errors_, now);
  }
  // Advances the manual clock one step; the request the last cycle submitted runs at the new time
  // (the drive answers it, or — while `answering_` is false — the client's response timeout ends
  // it without reaching the drive); then cycles.
  void step(const Order* order) {
    clock_.advance(kStep);
    script_.complete(clock_.now().mono, answering_ ? ErrorCode::kOk : ErrorCode::kTimeout);
    cycle(order);
  }
  void steps(const Order& order, int n) {
    for (int i = 0; i < n; ++i) step(&order);
  }
  template <class Predicate>
  bool step_until(const Order* order, Predicate done, int limit = 80) {
    for (int i = 0; i < limit; ++i) {
      step(order);
      if (done()) return true;
    }
    return false;
  }
  void reset_command() {
    logic_->reset();
    const Order reset = action("reset");
    step(&reset);
  }
  [[nodiscard]] std::string errors() const {
    std::string out;
    for (std::size_t i = 0; i < errors_.size(); ++i) out += std::string(errors_.at(i)) + "; ";
    return out;
  }
  [[nodiscard]] std::uint16_t drive_control_word() { return drive_.read(clock_.now().mono).control_word(); }
  // The control word the last submitted request writes (0 when it writes nothing).
  [[nodiscard]] std::uint16_t submitted_control_word() const {
    const hal::ModbusBatch& last = script_.submitted().back();
    return last.write_count > 0 ? last.write_values[ld::holding::kControlWord] : 0;
  }

  ManualClock clock_;
  LiftSettings settings_;
  hal::fake::LiftDrive drive_{hal::fake::LiftDriveConfig{}, clock_.now().mono};
  DriveScript script_{drive_};
  bool answering_ = true;
  std::optional<LiftLogic> logic_;
  LiftCommand command_{};
  LiftState state_{};
  runtime::ErrorList errors_;
};

// Nothing happens between cycles: no thread of the logic's reaches the drive. A cycle submits at
// most one request and never a second while one is in flight.
TEST_F(LiftLogicTest, TheLogicTalksToTheDriveOnlyFromItsCycle) {
  start();
  EXPECT_TRUE(script_.submitted().empty()) << "creating the logic sends nothing";
  const Order work = move("work");
  cycle(&work);
  ASSERT_EQ(script_.submitted().size(), 1u);
  const hal::ModbusBatch& first = script_.submitted()[0];
  EXPECT_EQ(first.read_bank, hal::ModbusRegisterBank::kInput);
  EXPECT_EQ(first.read_address, 0);
  EXPECT_EQ(first.read_count, ld::input::kCount);
  EXPECT_EQ(first.write_count, 0) << "no write before the drive's state is known";
  for (int i = 0; i < 2; ++i) {  // 200 ms, inside the request's deadline (300 ms)
    clock_.advance(kStep);
    cycle(&work);
  }
  EXPECT_EQ(script_.submitted().size(), 1u) << "one request in flight at a time";
  EXPECT_EQ(logic_->snapshot().rounds, 0u);
  EXPECT_EQ(drive_control_word(), 0) << "the drive heard nothing";

  script_.complete(clock_.now().mono);
  EXPECT_EQ(logic_->snapshot().rounds, 0u) << "a completion is taken by the cycle, not pushed into the logic";
  clock_.advance(kStep);
  cycle(&work);
  EXPECT_EQ(logic_->snapshot().rounds, 1u);
  EXPECT_TRUE(state_.drive_online);
  ASSERT_EQ(script_.submitted().size(), 2u);
  EXPECT_EQ(script_.submitted()[1].write_count, ld::holding::kCount);
  EXPECT_EQ(submitted_control_word(), ld::control::kEnable | ld::control::kMove);
  EXPECT_EQ(script_.submitted()[1].write_values[ld::holding::kTargetPosition], 1200);
}

// A reading is as old as the request that fetched it: judged from the time the logic submitted it,
// however late the cycle takes the completion.
TEST_F(LiftLogicTest, ACompletionOlderThanAnswerWithinReadsUnknown) {
  start();
  const Order home = move("home");
  const Time submitted = clock_.now().mono;
  cycle(&home);
  script_.complete(submitted + milliseconds(10));  // the drive answered at once...
  clock_.set(submitted + milliseconds(501));       // ...but the cycle came 501 ms later
  cycle(&home);
  EXPECT_EQ(logic_->snapshot().rounds, 1u);
  EXPECT_TRUE(logic_->snapshot().answered);
  EXPECT_EQ(logic_->snapshot().read_at, submitted);
  EXPECT_FALSE(state_.drive_online);
  EXPECT_EQ(state_.reading_age_ms, 501u);
  EXPECT_STREQ(state_.fault_text, "unknown");
  EXPECT_FALSE(state_.in_position) << "the drive is in position, but that reading is too old to say so";
  EXPECT_NE(errors().find("not answering for 0.50 s"), std::string::npos) << errors();

  // The same answer taken 500 ms after its request is current.
  close();
  DriveScript script(drive_);
  auto logic = LiftLogic::create(settings_, script.open(), clock_.now().mono);
  ASSERT_TRUE(logic) << logic.error().message;
  const Time again = clock_.now().mono;
  command_ = home.wire();
  logic->read_inputs(again);
  logic->update(&command_, again);
  script.complete(again + milliseconds(10));
  logic->read_inputs(again + milliseconds(500));
  state_ = LiftState{};
  errors_.clear();
  logic->report(state_, errors_, again + milliseconds(500));
  EXPECT_TRUE(state_.drive_online);
  EXPECT_EQ(state_.reading_age_ms, 500u);
  EXPECT_TRUE(state_.in_position);
  EXPECT_STREQ(state_.fault_text, "");
}

// A request the device never completes is reported as timed out at its deadline (the time the
// logic submitted it plus the request timeout), and the logic asks again.
TEST_F(LiftLogicTest, ARequestPastItsDeadlineIsATimeoutAndTheLogicAsksAgain) {
  start();
  const Order home = move("home");
  cycle(&home);
  clock_.advance(milliseconds(300));
  cycle(&home);
  EXPECT_EQ(logic_->snapshot().rounds, 0u) << "deadline not passed yet";
  EXPECT_EQ(script_.submitted().size(), 1u);
  clock_.advance(milliseconds(1));
  cycle(&home);
  EXPECT_EQ(logic_->snapshot().rounds, 1u);
  EXPECT_EQ(logic_->snapshot().last_error, ErrorCode::kTimeout);
  EXPECT_EQ(script_.submitted().size(), 2u) << "asked again in the same cycle";
  script_.complete(clock_.now().mono);
  step(&home);
  EXPECT_TRUE(state_.drive_online);
  EXPECT_EQ(logic_->snapshot().failures_in_a_row, 0u);
}

TEST_F(LiftLogicTest, MovesToANamedPositionAndReportsIt) {
  start();
  const Order work = move("work");
  step(&work);  // the first request reads the drive
  EXPECT_FALSE(state_.drive_online) << "no reading yet";
  step(&work);
  EXPECT_TRUE(state_.drive_online);
  EXPECT_STREQ(state_.target, "work");
  EXPECT_FLOAT_EQ(state_.target_mm, 120.0F);
  ASSERT_TRUE(step_until(&work, [&] { return state_.moving; })) << errors();
  EXPECT_TRUE(state_.enabled);
  EXPECT_FLOAT_EQ(state_.speed_mm_s, 100.0F) << "the hub file's speed, up";
  EXPECT_STREQ(state_.at, "");
  ASSERT_TRUE(step_until(&work, [&] { return std::string(state_.at) == "work"; })) << errors();
  EXPECT_TRUE(state_.in_position);
  EXPECT_FALSE(state_.moving);
  EXPECT_NEAR(state_.position_mm, 120.0, 0.5);
  EXPECT_NEAR(drive_.position_mm(clock_.now().mono), 120.0, 0.5);
  EXPECT_TRUE(errors_.empty()) << errors();

  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return std::string(state_.at) == "home"; })) << errors();
  EXPECT_NEAR(state_.position_mm, 380.0, 0.5);
  const Order floating = move("float");
  ASSERT_TRUE(step_until(&floating, [&] { return state_.moving; }));
  EXPECT_FLOAT_EQ(state_.speed_mm_s, -100.0F) << "down";
  ASSERT_TRUE(step_until(&floating, [&] { return std::string(state_.at) == "float"; }));
  EXPECT_NEAR(state_.position_mm, 250.0, 0.5);
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
  EXPECT_FALSE(state_.enabled);
}

TEST_F(LiftLogicTest, StopHaltsAndHolds) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.position_mm > 50.0F; }));
  const Order stop = action("stop");
  step(&stop);
  step(&stop);
  const float held = state_.position_mm;
  steps(stop, 5);
  EXPECT_FLOAT_EQ(state_.position_mm, held);
  EXPECT_FALSE(state_.moving);
  EXPECT_STREQ(state_.target, "");
  EXPECT_NE(drive_control_word() & ld::control::kStop, 0);
}

TEST_F(LiftLogicTest, NoCommandInForceStopsTheLift) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.position_mm > 50.0F; }));
  step(nullptr);
  step(nullptr);
  const float held = state_.position_mm;
  for (int i = 0; i < 5; ++i) step(nullptr);
  EXPECT_FLOAT_EQ(state_.position_mm, held);
  EXPECT_FALSE(state_.moving);
}

TEST_F(LiftLogicTest, EnterSafeStateAndShutdownStopTheDrive) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving; }));
  // The drive answered the request in flight; safe state comes before the next cycle and sends
  // "stop" at once, without waiting for a cycle.
  ASSERT_TRUE(script_.complete(clock_.now().mono));
  const std::size_t before = script_.submitted().size();
  logic_->enter_safe_state();
  ASSERT_EQ(script_.submitted().size(), before + 1);
  EXPECT_EQ(submitted_control_word(), ld::control::kStop | ld::control::kEnable) << "halt and hold";
  ASSERT_TRUE(script_.complete(clock_.now().mono));
  EXPECT_NE(drive_control_word() & ld::control::kStop, 0);

  ASSERT_TRUE(step_until(&home, [&] { return state_.moving; }));
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
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving; }));
  drive_.inject_overcurrent(clock_.now().mono);
  step(&home);
  EXPECT_TRUE(state_.fault);
  EXPECT_EQ(state_.fault_code, 1);
  EXPECT_STREQ(state_.fault_text, "overcurrent");
  EXPECT_FALSE(state_.enabled);
  EXPECT_NE(errors().find("lift drive fault 1 (overcurrent); lift stopped; send reset to clear"),
            std::string::npos)
      << errors();
  const float held = state_.position_mm;
  steps(home, 5);  // the planner keeps asking: nothing moves
  EXPECT_FLOAT_EQ(state_.position_mm, held);

  reset_command();
  ASSERT_TRUE(step_until(
      &home, [&] { return !state_.fault; }, 10))
      << "the reset pulse reached the drive";
  // The reset command took effect; the planner's next move is fresh: the drive needs an enable edge.
  const Order floating = move("float");
  ASSERT_TRUE(step_until(&floating, [&] { return std::string(state_.at) == "float"; })) << errors();
  EXPECT_TRUE(errors_.empty()) << errors();
}

TEST_F(LiftLogicTest, AJammedLoadTripsAFollowingErrorAndRecoversAfterReset) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving; }));
  drive_.set_blocked(true, clock_.now().mono);
  ASSERT_TRUE(step_until(&home, [&] { return state_.fault; }));
  EXPECT_EQ(state_.fault_code, 2);
  EXPECT_STREQ(state_.fault_text, "following error");
  drive_.set_blocked(false, clock_.now().mono);
  steps(home, 3);
  EXPECT_TRUE(state_.fault) << "latched in the drive until reset";
  reset_command();
  ASSERT_TRUE(step_until(&home, [&] { return std::string(state_.at) == "home"; })) << errors();
}

TEST_F(LiftLogicTest, AnOvertemperatureCannotBeResetWhileHot) {
  start();
  const Order work = move("work");
  ASSERT_TRUE(step_until(&work, [&] { return state_.moving; }));
  drive_.set_overtemperature(true, clock_.now().mono);
  ASSERT_TRUE(step_until(
      &work, [&] { return state_.fault; }, 5));
  reset_command();
  steps(work, 3);
  EXPECT_EQ(state_.fault_code, 3) << "refused while still hot";
  EXPECT_NE(errors().find("lift drive fault 3 (overtemperature)"), std::string::npos) << errors();
  drive_.set_overtemperature(false, clock_.now().mono);
  reset_command();
  ASSERT_TRUE(step_until(&work, [&] { return std::string(state_.at) == "work"; })) << errors();
}

TEST_F(LiftLogicTest, ADriveThatStopsAnsweringIsAnErrorNotAHang) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving; }));
  answering_ = false;
  step(&home);
  EXPECT_GT(logic_->snapshot().failures_in_a_row, 0u) << "the client's call timed out";
  EXPECT_EQ(logic_->snapshot().last_error, ErrorCode::kTimeout);
  steps(home, 5);  // 600 ms of manual time without an answer; the last reading's request 700 ms ago
  EXPECT_FALSE(state_.drive_online);
  EXPECT_NE(errors().find("not answering for 0.70 s"), std::string::npos) << errors();
  EXPECT_NE(errors().find("limit 0.50 s, last error: timeout); lift state unknown"), std::string::npos)
      << errors();

  answering_ = true;
  step(&home);
  EXPECT_TRUE(state_.drive_online);
  EXPECT_NE(errors().find("stopped answering for a while; send reset to clear"), std::string::npos)
      << errors();
  // That request only read the drive (nothing is written without a current reading); "stop" goes
  // out with the next one, decided from this reading.
  EXPECT_EQ(submitted_control_word(), ld::control::kStop | ld::control::kEnable);
  step(&home);
  const float held = state_.position_mm;
  steps(home, 3);
  EXPECT_FLOAT_EQ(state_.position_mm, held) << "latched: no motion until reset";
  reset_command();
  EXPECT_TRUE(errors_.empty()) << errors();
  const Order work = move("work");
  ASSERT_TRUE(step_until(&work, [&] { return std::string(state_.at) == "work"; })) << errors();
}

// The drive stops answering mid-move. Its last reading (moving up at 100 mm/s) holds for
// answer_within (500 ms); after that the State shows nothing of it as current, while the drive
// really does carry on until its own communication watchdog (1000 ms, from the hub file) stops it.
TEST_F(LiftLogicTest, AReadingOlderThanItsValidityIsUnknownUntilAFreshOneConfirmsTheLift) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving && state_.position_mm > 20.0F; }));
  answering_ = false;
  step(&home);
  ASSERT_GT(logic_->snapshot().failures_in_a_row, 0u);
  const Time last_read = logic_->snapshot().read_at;
  const float last_seen_mm = state_.position_mm;

  clock_.set(last_read + milliseconds(500));  // the reading's last valid moment
  cycle(&home);
  EXPECT_TRUE(state_.drive_online);
  EXPECT_EQ(state_.reading_age_ms, 500u);
  EXPECT_TRUE(state_.moving) << "still within its validity";

  clock_.set(last_read + milliseconds(501));
  cycle(&home);
  EXPECT_FALSE(state_.drive_online);
  EXPECT_EQ(state_.reading_age_ms, 501u);
  EXPECT_FALSE(state_.moving) << "never true from a stale reading";
  EXPECT_FALSE(state_.enabled);
  EXPECT_FALSE(state_.in_position);
  EXPECT_FALSE(state_.fault);
  EXPECT_EQ(state_.fault_code, 0);
  EXPECT_STREQ(state_.fault_text, "unknown");
  EXPECT_STREQ(state_.at, "");
  EXPECT_EQ(state_.position_mm, 0.0F);
  EXPECT_EQ(state_.speed_mm_s, 0.0F);
  EXPECT_STREQ(state_.target, "home") << "the command's target is the hub's own, not a reading";
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
  EXPECT_EQ(state_.reading_age_ms, 1200u);
  EXPECT_FALSE(state_.moving);
  const auto drive = drive_.read(clock_.now().mono);
  EXPECT_EQ(drive.input[ld::input::kFaultCode], static_cast<std::uint16_t>(ld::FaultCode::kWatchdog));
  EXPECT_EQ(drive.input[ld::input::kStatusWord] & ld::status::kMoving, 0);

  // A fresh reading confirms it: stopped by its watchdog, values current again.
  answering_ = true;
  step(&home);
  EXPECT_TRUE(state_.drive_online);
  EXPECT_LE(state_.reading_age_ms, 100u);
  EXPECT_FALSE(state_.moving);
  EXPECT_TRUE(state_.fault);
  EXPECT_EQ(state_.fault_code, 4);
  EXPECT_STREQ(state_.fault_text, "communication watchdog");
  EXPECT_NEAR(state_.position_mm, drive_.position_mm(clock_.now().mono), 0.15);  // register: 0.1 mm
  EXPECT_GT(state_.position_mm, last_seen_mm + 80.0F) << "where the drive went on its own";
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
  EXPECT_FALSE(state_.drive_online);
  EXPECT_EQ(state_.reading_age_ms, kNeverRead);
  EXPECT_FALSE(state_.moving);
  EXPECT_STREQ(state_.fault_text, "unknown");
  EXPECT_NE(errors().find("no answer since start (last error: timeout); lift state unknown"),
            std::string::npos)
      << errors();
  // A drive that comes up after the hub is normal operation: not latched.
  answering_ = true;
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving; })) << errors();
}

TEST_F(LiftLogicTest, BadMoveCommandsAreRejectedWithTheirReason) {
  start();
  runtime::Problem problem;
  LiftCommand command{};
  const Order up = move("attic");
  command = up.wire();
  EXPECT_FALSE(logic_->validate(command, problem));
  EXPECT_EQ(problem.view(), "unknown position 'attic' (expected one of: home, float, work)");
  const Order empty = move("");
  command = empty.wire();
  EXPECT_FALSE(logic_->validate(command, problem));
  EXPECT_EQ(problem.view(), "unknown position '' (expected one of: home, float, work)");
  Order stop = action("stop");
  stop.position = "attic";
  command = stop.wire();
  EXPECT_TRUE(logic_->validate(command, problem)) << "stop ignores the position";
}

}  // namespace
}  // namespace hubrt::tool_ecu
