// The lift node against the lift-drive simulator behind a real libmodbus TCP server on loopback,
// through the fake backend's real libmodbus client. The drive and the node's logic run on the
// manual clock; the Modbus worker is a real thread, so each step waits (real time, with a
// deadline) until the worker has read the drive at the new manual time.
#include "lift_logic.h"

#include <chrono>
#include <functional>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/protocol/lift_drive_modbus.h"

#include "reading_age.h"

namespace hubrt::tool_ecu {
namespace {

namespace ld = protocol::lift_drive;
using hal::fake::FakeBackend;
using std::chrono::milliseconds;
using std::chrono::seconds;

// Real-time patience for the worker thread: generous, for a loaded 2-core machine running
// sanitizer builds in parallel. The tests check behaviour, not timing.
constexpr auto kPatience = seconds(20);
constexpr auto kStep = milliseconds(100);  // manual time per cycle; well inside answer_within (500 ms)

struct Order {
  std::string action;
  std::string position;
  std::string target_name = "lift";
  std::string target_type = "lift";

  [[nodiscard]] hub_msgs::LiftCommand message() const {
    hub_msgs::LiftCommand command;
    command.set_target_type(target_type);
    command.set_target_name(target_name);
    command.set_action(action);
    command.set_position(position);
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
    auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/tool_ecu/tool_ecu.yaml");
    ASSERT_TRUE(config) << config.error().message;
    for (const auto& node : config->nodes) {
      if (node.type == LiftLogic::kType) {
        auto settings = parse_lift_settings(node);
        ASSERT_TRUE(settings) << settings.error().message;
        settings_ = std::move(*settings);
      }
    }
    auto fake = FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
    drive_ = fake_->lift_drive("lift_drive");
    server_ = fake_->lift_drive_server("lift_drive");
    ASSERT_NE(drive_, nullptr);
    ASSERT_NE(server_, nullptr);
  }
  void TearDown() override { logic_.reset(); }  // the worker stops before the server goes

  void start() {
    auto logic = LiftLogic::create(settings_, board_, *fake_, clock_);
    ASSERT_TRUE(logic) << logic.error().message;
    logic_.emplace(std::move(*logic));
  }

  // Waits (real time) until the worker's snapshot satisfies `done`.
  bool wait_worker(const std::function<bool(const LiftSnapshot&)>& done, Duration patience = kPatience) {
    const auto deadline = std::chrono::steady_clock::now() + patience;
    while (std::chrono::steady_clock::now() < deadline) {
      if (done(logic_->snapshot())) return true;
      std::this_thread::sleep_for(milliseconds(1));
    }
    return false;
  }

  // One cycle at the current manual time, as the Node runs it.
  void cycle(const Order* order) {
    const Time now = clock_.now().mono;
    if (order != nullptr) command_ = order->message();
    logic_->read_inputs(now);
    const hub_msgs::LiftCommandView in_force = command_.view();
    logic_->update(order == nullptr ? nullptr : &in_force, now);
    errors_.clear();
    state_ = hub_msgs::LiftState();
    logic_->report(state_, errors_, now);
  }
  // Advances the manual clock one step, lets the worker read the drive at that time (two rounds:
  // the first may have begun before the advance), then cycles.
  void step(const Order* order) {
    clock_.advance(kStep);
    const Time now = clock_.now().mono;
    const std::uint64_t rounds = logic_->snapshot().rounds;
    ASSERT_TRUE(wait_worker([&](const LiftSnapshot& s) {
      return s.answered && s.read_at >= now && s.rounds >= rounds + 2;
    })) << "the worker did not read the drive within "
        << kPatience.count() << " s";
    cycle(order);
  }
  void steps(const Order& order, int n) {
    for (int i = 0; i < n; ++i) step(&order);
  }
  template <class Predicate>
  bool step_until(const Order* order, Predicate done, int limit = 80) {
    for (int i = 0; i < limit; ++i) {
      step(order);
      if (::testing::Test::HasFatalFailure()) return false;
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
  [[nodiscard]] std::uint16_t drive_control_word() { return drive_->read(clock_.now().mono).control_word(); }

  ManualClock clock_;
  hal::BoardConfig board_;
  LiftSettings settings_;
  std::unique_ptr<FakeBackend> fake_;
  hal::fake::LiftDrive* drive_ = nullptr;
  hal::fake::LiftDriveServer* server_ = nullptr;
  std::optional<LiftLogic> logic_;
  hub_msgs::LiftCommand command_;
  hub_msgs::LiftState state_;
  runtime::ErrorList errors_;
};

TEST_F(LiftLogicTest, MovesToANamedPositionAndReportsIt) {
  start();
  const Order work = move("work");
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
  EXPECT_NEAR(drive_->position_mm(clock_.now().mono), 120.0, 0.5);
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
  step(&stop);
  const auto registers = drive_->read(clock_.now().mono);
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
  logic_->enter_safe_state();
  ASSERT_TRUE(
      wait_worker([](const LiftSnapshot& s) { return (s.written_control & ld::control::kStop) != 0; }));
  EXPECT_NE(drive_control_word() & ld::control::kStop, 0);

  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  EXPECT_EQ(drive_control_word() & ld::control::kStop, 0);
  logic_.reset();  // the worker writes "stop" on its way out
  EXPECT_NE(drive_control_word() & ld::control::kStop, 0);
}

TEST_F(LiftLogicTest, ADriveFaultStopsLatchesAndNeedsResetAndAFreshMove) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  drive_->inject_overcurrent(clock_.now().mono);
  step(&home);
  EXPECT_TRUE(state_.fault());
  EXPECT_EQ(state_.fault_code(), 1);
  EXPECT_EQ(state_.fault_text(), "overcurrent");
  EXPECT_FALSE(state_.enabled());
  EXPECT_NE(errors().find("lift drive fault 1 (overcurrent); lift stopped; send reset to clear"),
            std::string::npos)
      << errors();
  const float held = state_.position_mm();
  steps(home, 5);  // the planner keeps asking: nothing moves
  EXPECT_FLOAT_EQ(state_.position_mm(), held);

  reset_command();
  ASSERT_TRUE(step_until(
      &home, [&] { return !state_.fault(); }, 10))
      << "the reset pulse reached the drive";
  // The reset command took effect; the planner's next move is fresh: the drive needs an enable edge.
  const Order floating = move("float");
  ASSERT_TRUE(step_until(&floating, [&] { return std::string(state_.at()) == "float"; })) << errors();
  EXPECT_TRUE(errors_.empty()) << errors();
}

TEST_F(LiftLogicTest, AJammedLoadTripsAFollowingErrorAndRecoversAfterReset) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  drive_->set_blocked(true, clock_.now().mono);
  ASSERT_TRUE(step_until(&home, [&] { return state_.fault(); }));
  EXPECT_EQ(state_.fault_code(), 2);
  EXPECT_EQ(state_.fault_text(), "following error");
  drive_->set_blocked(false, clock_.now().mono);
  steps(home, 3);
  EXPECT_TRUE(state_.fault()) << "latched in the drive until reset";
  reset_command();
  ASSERT_TRUE(step_until(&home, [&] { return std::string(state_.at()) == "home"; })) << errors();
}

TEST_F(LiftLogicTest, AnOvertemperatureCannotBeResetWhileHot) {
  start();
  const Order work = move("work");
  ASSERT_TRUE(step_until(&work, [&] { return state_.moving(); }));
  drive_->set_overtemperature(true, clock_.now().mono);
  ASSERT_TRUE(step_until(
      &work, [&] { return state_.fault(); }, 5));
  reset_command();
  steps(work, 3);
  EXPECT_EQ(state_.fault_code(), 3) << "refused while still hot";
  EXPECT_NE(errors().find("lift drive fault 3 (overtemperature)"), std::string::npos) << errors();
  drive_->set_overtemperature(false, clock_.now().mono);
  reset_command();
  ASSERT_TRUE(step_until(&work, [&] { return std::string(state_.at()) == "work"; })) << errors();
}

TEST_F(LiftLogicTest, ADriveThatStopsAnsweringIsAnErrorNotAHang) {
  start();
  const Order home = move("home");
  ASSERT_TRUE(step_until(&home, [&] { return state_.moving(); }));
  server_->set_answering(false);
  ASSERT_TRUE(wait_worker([](const LiftSnapshot& s) { return s.failures_in_a_row > 0; }))
      << "the worker's call timed out";
  EXPECT_EQ(logic_->snapshot().last_error, ErrorCode::kTimeout);
  for (int i = 0; i < 6; ++i) {  // 600 ms of manual time without an answer
    clock_.advance(kStep);
    const auto started = std::chrono::steady_clock::now();
    cycle(&home);
    // The cycle never waits for the drive. Bound generous (a loaded machine may deschedule us):
    // a blocking Modbus call would take the 100 ms response timeout at least.
    EXPECT_LT(std::chrono::steady_clock::now() - started, milliseconds(50));
  }
  EXPECT_FALSE(state_.drive_online());
  EXPECT_NE(errors().find("not answering for 0.6"), std::string::npos) << errors();
  EXPECT_NE(errors().find("limit 0.50 s, last error: timeout); lift state unknown"), std::string::npos)
      << errors();

  server_->set_answering(true);
  ASSERT_TRUE(wait_worker(
      [&](const LiftSnapshot& s) { return s.failures_in_a_row == 0 && s.read_at >= clock_.now().mono; }));
  step(&home);
  EXPECT_TRUE(state_.drive_online());
  EXPECT_NE(errors().find("stopped answering for a while; send reset to clear"), std::string::npos)
      << errors();
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
  server_->set_answering(false);
  ASSERT_TRUE(wait_worker([](const LiftSnapshot& s) { return s.failures_in_a_row > 0; }));
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
  EXPECT_EQ(state_.position_mm(), 0.0F);
  EXPECT_EQ(state_.speed_mm_s(), 0.0F);
  EXPECT_EQ(state_.target(), "home") << "the command's target is the hub's own, not a reading";
  EXPECT_EQ(errors().find("stopped"), std::string::npos) << "nobody knows it stopped: " << errors();
  EXPECT_NE(errors().find(fmt::format("lift motion unknown: last seen at {:.1f} mm, moving; the drive's own "
                                      "watchdog stops it 1000 ms after the last request it got",
                                      last_seen_mm)),
            std::string::npos)
      << errors();
  // Indeed the simulated drive moved on: 50 mm in those 500 ms.
  EXPECT_GT(drive_->position_mm(clock_.now().mono), last_seen_mm + 40.0);

  // Its watchdog trips 1000 ms after the last request it got (about the last read).
  clock_.set(last_read + milliseconds(1200));
  cycle(&home);
  EXPECT_EQ(state_.reading_age_ms(), 1200u);
  EXPECT_FALSE(state_.moving());
  const auto drive = drive_->read(clock_.now().mono);
  EXPECT_EQ(drive.input[ld::input::kFaultCode], static_cast<std::uint16_t>(ld::FaultCode::kWatchdog));
  EXPECT_EQ(drive.input[ld::input::kStatusWord] & ld::status::kMoving, 0);

  // A fresh reading confirms it: stopped by its watchdog, values current again.
  server_->set_answering(true);
  step(&home);
  EXPECT_TRUE(state_.drive_online());
  EXPECT_LE(state_.reading_age_ms(), 100u);
  EXPECT_FALSE(state_.moving());
  EXPECT_TRUE(state_.fault());
  EXPECT_EQ(state_.fault_code(), 4);
  EXPECT_EQ(state_.fault_text(), "communication watchdog");
  EXPECT_NEAR(state_.position_mm(), drive_->position_mm(clock_.now().mono), 0.15);  // register: 0.1 mm
  EXPECT_GT(state_.position_mm(), last_seen_mm + 80.0F) << "where the drive went on its own";
  EXPECT_EQ(errors().find("lift motion unknown"), std::string::npos) << errors();
  EXPECT_NE(errors().find("stopped answering for a while; send reset to clear"), std::string::npos)
      << errors();
}

TEST_F(LiftLogicTest, ADriveThatNeverAnswersIsReportedAfterTheLimit) {
  server_->set_answering(false);
  start();
  const Order home = move("home");
  ASSERT_TRUE(wait_worker([](const LiftSnapshot& s) { return s.failures_in_a_row > 0; }));
  clock_.advance(milliseconds(400));
  cycle(&home);
  EXPECT_TRUE(errors_.empty()) << "not yet: " << errors();
  clock_.advance(milliseconds(200));
  cycle(&home);
  EXPECT_FALSE(state_.drive_online());
  EXPECT_EQ(state_.reading_age_ms(), kNeverRead);
  EXPECT_FALSE(state_.moving());
  EXPECT_EQ(state_.fault_text(), "unknown");
  EXPECT_NE(errors().find("no answer since start (last error: timeout); lift state unknown"),
            std::string::npos)
      << errors();
  // A drive that comes up after the hub is normal operation: not latched.
  server_->set_answering(true);
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
}  // namespace hubrt::tool_ecu
