// The tool-changer logic on the simulation board's fake backend (valves with actuation delays and
// supply pressure, settable tool-ID lines) with a manual clock: every interlock both ways, every
// safe state, pressure and gripper faults, and recovery after a reset.
#include "rsp_logic.h"

#include <optional>

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"

#include "rsp_test_support.h"

namespace hubrt::rsp_ecu {
namespace {

using std::chrono::milliseconds;
using testing::command;
using testing::dock_slots;
using testing::DockFeed;
using testing::OwnedCommand;

constexpr Duration kCycle = milliseconds(10);

class RspLogicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/rsp_ecu/rsp_ecu.yaml");
    ASSERT_TRUE(config) << config.error().message;
    auto settings = parse_rsp_settings(config->nodes.at(0));
    ASSERT_TRUE(settings) << settings.error().message;
    settings_ = std::move(*settings);
    auto fake = hal::fake::FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
  }

  RspLogic make_logic() {
    auto logic = testing::make_rsp_logic(settings_, board_, *fake_, dock_.input(), clock_.now().mono);
    EXPECT_TRUE(logic) << logic.error().message;
    return std::move(*logic);
  }

  // The Dock ECU keeps publishing this (every cycle) until dock_silent().
  void dock_reports(bool ladder_frame_home, bool filter_home, bool smart_home) {
    dock_slots_ = dock_slots(ladder_frame_home, filter_home, smart_home);
  }
  void dock_silent() { dock_slots_.reset(); }

  // The tool-ID lines show `tool` ("none": no line).
  void tool_on_changer(std::string_view tool) {
    for (const std::string_view name : {"ladder_frame_tool", "smart_tool", "filter_tool"}) {
      set_input(std::string("rsp.tool_id.") + std::string(name), tool == name);
    }
  }
  void set_input(const std::string& signal, bool active) {
    hal::fake::SettableInput* input = fake_->input(signal);
    ASSERT_NE(input, nullptr) << signal;
    input->set(active);
  }

  // One cycle at the current time; returns the State the logic reports.
  hub_msgs::RspState cycle(RspLogic& logic, OwnedCommand* in_force) {
    const Time now = clock_.now().mono;
    if (dock_slots_) dock_.arrive(*dock_slots_, now);
    logic.read_inputs(now);
    std::optional<hub_msgs::RspCommandView> view;
    if (in_force != nullptr) view = in_force->view();
    logic.update(view ? &*view : nullptr, now);
    errors_.clear();
    hub_msgs::RspState state;
    logic.report(state, errors_, now);
    return state;
  }
  // Cycles every 10 ms for `span` (the first at once); returns the last State.
  hub_msgs::RspState run_for(RspLogic& logic, Duration span, OwnedCommand* in_force) {
    hub_msgs::RspState state = cycle(logic, in_force);
    for (Duration t = kCycle; t <= span; t += kCycle) {
      clock_.advance(kCycle);
      state = cycle(logic, in_force);
    }
    return state;
  }

  bool output(std::string_view signal) {
    auto level = fake_->active(signal);
    EXPECT_TRUE(level.is_ok()) << signal;
    return level.value_or(false);
  }
  bool lock_valve_energised() { return output("rsp.lock_valve"); }
  bool gripper_valve_energised() { return output("rsp.gripper_valve"); }

  ManualClock clock_;
  hal::BoardConfig board_;
  RspSettings settings_;
  std::unique_ptr<hal::fake::FakeBackend> fake_;
  DockFeed dock_{milliseconds(500)};
  std::optional<std::vector<std::pair<std::string, bool>>> dock_slots_;
  runtime::ErrorList errors_;
};

// --- Start-up and decoding -------------------------------------------------------------------------

TEST_F(RspLogicTest, StartsLockedWithTheGripperAsTheBoardOpensIt) {
  RspLogic logic = make_logic();
  hub_msgs::RspState state = cycle(logic, nullptr);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(gripper_valve_energised()) << "host-sim.yaml: the gripper line opens closed (initial: true)";
  EXPECT_EQ(state.lock(), "closing") << "until a full stroke has passed the lock may still be closing";
  EXPECT_FALSE(state.locked());
  EXPECT_TRUE(state.safe_state());
  EXPECT_EQ(state.gripper(), "grab");

  state = run_for(logic, milliseconds(200), nullptr);
  EXPECT_EQ(state.tool(), "smart_tool") << "host-sim.yaml: the robot starts holding the smart tool";
  EXPECT_EQ(state.lock(), "closed");
  EXPECT_TRUE(state.locked());
  EXPECT_TRUE(state.pressure_ok());
  EXPECT_EQ(state.gripper_confirm(), "connected");
  EXPECT_FALSE(state.unlock_allowed());
  EXPECT_NE(std::string_view(state.unlock_blocked()).find("no Dock ECU State received yet"),
            std::string_view::npos)
      << state.unlock_blocked();
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
}

TEST_F(RspLogicTest, DecodesTheToolIdLinesAndReportsAnUndefinedOne) {
  RspLogic logic = make_logic();
  for (const std::string_view tool : {"ladder_frame_tool", "filter_tool", "none", "smart_tool"}) {
    tool_on_changer(tool);
    const hub_msgs::RspState state = run_for(logic, milliseconds(50), nullptr);  // past the 20 ms debounce
    EXPECT_EQ(state.tool(), tool);
  }
  hub_msgs::RspState state = run_for(logic, milliseconds(200), nullptr);
  EXPECT_TRUE(state.locked());
  tool_on_changer("none");
  state = run_for(logic, milliseconds(50), nullptr);
  EXPECT_FALSE(state.locked()) << "locked means locked onto a tool";

  tool_on_changer("smart_tool");
  set_input("rsp.tool_id.filter_tool", true);
  state = run_for(logic, milliseconds(50), nullptr);
  EXPECT_EQ(state.tool(), "undefined");
  EXPECT_FALSE(state.locked());
  EXPECT_TRUE(errors_.contains("tool id undefined: 2 tool-ID lines set at once (smart_tool, filter_tool)"))
      << errors_.at(0);
}

// --- The unlock interlock, both ways --------------------------------------------------------------

TEST_F(RspLogicTest, UnlockOpensTheChangerWhenTheDockReportsThatToolHome) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  hub_msgs::RspState state = cycle(logic, &unlock);
  EXPECT_TRUE(state.unlock_allowed());
  EXPECT_EQ(state.unlock_blocked(), "");
  EXPECT_TRUE(lock_valve_energised());
  EXPECT_EQ(state.lock(), "opening");
  EXPECT_FALSE(state.locked());
  EXPECT_FALSE(state.safe_state());
  state = run_for(logic, milliseconds(200), &unlock);
  EXPECT_EQ(state.lock(), "open");
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);

  // The robot moves away: the tool stays in the dock, the ID lines go quiet, the changer stays open.
  tool_on_changer("none");
  state = run_for(logic, milliseconds(50), &unlock);
  EXPECT_EQ(state.tool(), "none");
  EXPECT_TRUE(lock_valve_energised());

  OwnedCommand lock = command("lock");
  state = cycle(logic, &lock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_EQ(state.lock(), "closing");
}

TEST_F(RspLogicTest, UnlockIsRefusedWhenTheToolIsNotHome) {
  RspLogic logic = make_logic();
  dock_reports(true, true, false);  // the smart tool is on the robot, not in its slot
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspState state = run_for(logic, milliseconds(500), &unlock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(fake_->history("rsp.lock_valve").empty() || !fake_->history("rsp.lock_valve").back().active);
  for (const auto& change : fake_->history("rsp.lock_valve")) EXPECT_FALSE(change.active) << "never opened";
  EXPECT_TRUE(state.locked());
  EXPECT_FALSE(state.unlock_allowed());
  EXPECT_EQ(state.unlock_blocked(), "the Dock ECU does not report smart_tool home (slot 'smart_tool' empty)");
  ASSERT_EQ(errors_.size(), 1u);
  EXPECT_EQ(errors_.at(0),
            "unlock refused: the Dock ECU does not report smart_tool home (slot 'smart_tool' empty); lock "
            "kept closed");
}

TEST_F(RspLogicTest, UnlockIsRefusedWhenOnlyAnotherToolIsHome) {
  RspLogic logic = make_logic();
  tool_on_changer("filter_tool");
  dock_reports(true, false, true);  // ladder-frame and smart tools home, the filter tool is not
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspState state = run_for(logic, milliseconds(300), &unlock);
  EXPECT_EQ(state.tool(), "filter_tool");
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors_.contains("filter_tool home (slot 'filter_tool' empty)"));
}

TEST_F(RspLogicTest, UnlockIsRefusedWhenTheDockStateWasNeverReceived) {
  RspLogic logic = make_logic();
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(300), &unlock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(
      errors_.contains("unlock refused: cannot confirm smart_tool is home: no Dock ECU State received yet "
                       "(/dock_ecu/dock/state); lock kept closed"))
      << errors_.at(0);
}

TEST_F(RspLogicTest, AnOpenChangerClosesTheCycleTheDockStateGoesStale) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  dock_silent();
  run_for(logic, milliseconds(500), &unlock);
  EXPECT_TRUE(lock_valve_energised()) << "500 ms without a Dock State is still within its timeout";
  clock_.advance(kCycle);
  const hub_msgs::RspState state = cycle(logic, &unlock);
  EXPECT_FALSE(lock_valve_energised()) << "lost the moment it is older than the timeout";
  EXPECT_EQ(state.lock(), "closing");
  EXPECT_TRUE(errors_.contains("Dock ECU State older than 0.50 s (/dock_ecu/dock/state)")) << errors_.at(0);

  dock_reports(true, true, true);
  cycle(logic, &unlock);
  EXPECT_TRUE(lock_valve_energised()) << "the command in force acts again once the dock confirms";
}

TEST_F(RspLogicTest, AnOpenChangerClosesWhenTheDockNoLongerReportsTheToolHome) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(100), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  dock_reports(true, true, false);
  cycle(logic, &unlock);
  EXPECT_FALSE(lock_valve_energised());
}

TEST_F(RspLogicTest, AnUndefinedToolIdRefusesUnlockEvenWithEverySlotOccupied) {
  RspLogic logic = make_logic();
  tool_on_changer("smart_tool");
  set_input("rsp.tool_id.ladder_frame_tool", true);
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspState state = run_for(logic, milliseconds(300), &unlock);
  EXPECT_EQ(state.tool(), "undefined");
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors_.contains("unlock refused: tool id undefined"));
}

TEST_F(RspLogicTest, AnUnreadableToolIdLineRefusesUnlock) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  auto wiring = fake_->wiring("rsp.tool_id.ladder_frame_tool");
  ASSERT_TRUE(wiring.is_ok());
  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, true).is_ok());
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspState state = run_for(logic, milliseconds(100), &unlock);
  EXPECT_EQ(state.tool(), "undefined") << "a line that cannot be read might be the tool that is there";
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors_.contains("input rsp.tool_id.ladder_frame_tool failed to read: i/o error"))
      << errors_.at(0);
}

TEST_F(RspLogicTest, WithNoToolTheChangerOpensOnlyWhileTheDockIsAlive) {
  RspLogic logic = make_logic();
  tool_on_changer("none");
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(100), &unlock);
  EXPECT_FALSE(lock_valve_energised()) << "no Dock State: not allowed, even with nothing to drop";
  dock_reports(false, false, false);
  cycle(logic, &unlock);
  EXPECT_TRUE(lock_valve_energised());
}

TEST_F(RspLogicTest, ValidateRejectsAnUnlockTheInterlockDoesNotAllow) {
  RspLogic logic = make_logic();
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspCommandView wire = unlock.view();
  runtime::Problem problem;
  EXPECT_FALSE(logic.validate(wire, problem)) << "nothing evaluated yet: not allowed";
  dock_reports(true, true, false);
  run_for(logic, milliseconds(50), nullptr);
  EXPECT_FALSE(logic.validate(wire, problem));
  EXPECT_EQ(problem.view(),
            "unlock refused: the Dock ECU does not report smart_tool home (slot 'smart_tool' empty); lock "
            "kept closed");
  dock_reports(true, true, true);
  cycle(logic, nullptr);
  EXPECT_TRUE(logic.validate(wire, problem));
  OwnedCommand lock = command("lock");
  dock_silent();
  clock_.advance(milliseconds(600));
  cycle(logic, nullptr);
  EXPECT_TRUE(logic.validate(lock.view(), problem)) << "locking is always allowed";
}

TEST_F(RspLogicTest, ValidateRejectsAnUnknownGripperState) {
  RspLogic logic = make_logic();
  runtime::Problem problem;
  for (const std::string_view good : {"grab", "release", "keep", ""}) {
    OwnedCommand c = command("lock", good);
    EXPECT_TRUE(logic.validate(c.view(), problem)) << good;
  }
  OwnedCommand bad = command("lock", "open");
  EXPECT_FALSE(logic.validate(bad.view(), problem));
  EXPECT_EQ(problem.view(), "unknown gripper state 'open' (expected grab, release, keep, or empty for keep)");
  OwnedCommand shouting = command("reset", "GRAB");
  EXPECT_FALSE(logic.validate(shouting.view(), problem)) << "exact strings only";
}

// --- The gripper -----------------------------------------------------------------------------------

TEST_F(RspLogicTest, TheGripperFollowsItsCommandAndKeepLeavesItAsItIs) {
  RspLogic logic = make_logic();
  tool_on_changer("ladder_frame_tool");
  OwnedCommand release = command("lock", "release");
  hub_msgs::RspState state = run_for(logic, milliseconds(300), &release);
  EXPECT_FALSE(gripper_valve_energised());
  EXPECT_EQ(state.gripper(), "release");
  EXPECT_EQ(state.gripper_confirm(), "not_connected");
  OwnedCommand keep = command("lock", "keep");
  run_for(logic, milliseconds(100), &keep);
  EXPECT_FALSE(gripper_valve_energised());
  OwnedCommand grab = command("lock", "grab");
  state = cycle(logic, &grab);
  EXPECT_TRUE(gripper_valve_energised());
  EXPECT_EQ(state.gripper_confirm(), "not_connected") << "the gripper takes 150 ms to close";
  state = run_for(logic, milliseconds(300), &grab);
  EXPECT_EQ(state.gripper_confirm(), "connected");
  OwnedCommand empty = command("lock", "");
  run_for(logic, milliseconds(100), &empty);
  EXPECT_TRUE(gripper_valve_energised());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
}

TEST_F(RspLogicTest, AGripThatFailsIsLatchedAfterTheConfirmDelayAndHoldsTheSafeState) {
  RspLogic logic = make_logic();
  tool_on_changer("ladder_frame_tool");
  dock_reports(true, true, false);
  OwnedCommand release = command("lock", "release");
  run_for(logic, milliseconds(300), &release);
  fake_->valve("rsp.gripper_valve")->stick(true);  // the gripper jams open
  OwnedCommand grab = command("lock", "grab");
  hub_msgs::RspState state = run_for(logic, milliseconds(490), &grab);
  EXPECT_FALSE(logic.fault_latched()) << "within the 500 ms confirm delay nothing is called failed";
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
  state = run_for(logic, milliseconds(20), &grab);
  ASSERT_TRUE(logic.fault_latched());
  EXPECT_TRUE(errors_.contains("gripper failed to grab: confirm lines still show not_connected after"))
      << errors_.at(0);
  EXPECT_TRUE(errors_.contains("latched: lock held closed, gripper as it is; reset to clear"));
  EXPECT_TRUE(state.safe_state());
  EXPECT_TRUE(gripper_valve_energised()) << "the gripper stays as it is";

  // While latched, no gripper or lock command acts.
  OwnedCommand release_again = command("lock", "release");
  run_for(logic, milliseconds(100), &release_again);
  EXPECT_TRUE(gripper_valve_energised());
  dock_reports(true, true, true);
  tool_on_changer("ladder_frame_tool");
  OwnedCommand unlock = command("unlock");
  state = run_for(logic, milliseconds(100), &unlock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_EQ(state.unlock_blocked(), "a gripper failure is latched; reset first");
}

TEST_F(RspLogicTest, ConfirmLinesThatDisagreeAreLatchedAsAFailedGripper) {
  RspLogic logic = make_logic();
  tool_on_changer("ladder_frame_tool");
  OwnedCommand grab = command("lock", "grab");
  run_for(logic, milliseconds(300), &grab);
  fake_->valve("rsp.gripper_valve")->fail_confirm(1, false);  // sensor B drops out
  hub_msgs::RspState state = run_for(logic, milliseconds(400), &grab);
  EXPECT_EQ(state.gripper_confirm(), "moving");
  EXPECT_FALSE(logic.fault_latched());
  state = run_for(logic, milliseconds(200), &grab);
  EXPECT_EQ(state.gripper_confirm(), "failed");
  EXPECT_TRUE(errors_.contains("gripper failed: confirm lines disagree (A on, B off) for more than 500 ms"))
      << errors_.at(0);
}

TEST_F(RspLogicTest, TheGripperIsNotSupervisedWithoutItsTool) {
  RspLogic logic = make_logic();  // the smart tool is on the changer: it has no gripper
  fake_->valve("rsp.gripper_valve")->stick(true);
  OwnedCommand release = command("lock", "release");
  run_for(logic, milliseconds(2000), &release);
  EXPECT_FALSE(logic.fault_latched());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
}

// --- Pressure --------------------------------------------------------------------------------------

TEST_F(RspLogicTest, APressureDropMidOperationLatchesAndHoldsTheSafeStateUntilReset) {
  RspLogic logic = make_logic();
  tool_on_changer("ladder_frame_tool");
  dock_reports(true, true, false);
  OwnedCommand grab = command("lock", "grab");
  run_for(logic, milliseconds(300), &grab);
  // Mid-operation: the planner releases the ladder frame, and the air goes as the valve moves.
  OwnedCommand release = command("lock", "release");
  cycle(logic, &release);
  ASSERT_FALSE(gripper_valve_energised());
  fake_->pressure_supply("main_air")->drop();
  hub_msgs::RspState state = run_for(logic, milliseconds(100), &release);  // past the switch's 50 ms debounce
  EXPECT_FALSE(state.pressure_ok());
  EXPECT_TRUE(state.pressure_known()) << "a switch that reads off is a known pressure loss";
  EXPECT_TRUE(state.safe_state());
  EXPECT_TRUE(
      errors_.contains("pressure failure: supply pressure lost (rsp.pressure_ok off) (latched: lock held "
                       "closed, gripper as it is; reset to clear)"))
      << errors_.at(0);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_FALSE(gripper_valve_energised()) << "gripper as it is";
  EXPECT_FALSE(errors_.contains("gripper failed")) << "a gripper without air is not a failed gripper";

  OwnedCommand grab_again = command("lock", "grab");
  run_for(logic, milliseconds(100), &grab_again);
  EXPECT_FALSE(gripper_valve_energised()) << "no command acts while the fault is latched";

  fake_->pressure_supply("main_air")->restore();
  state = run_for(logic, milliseconds(1000), &grab_again);
  EXPECT_TRUE(state.pressure_ok());
  EXPECT_TRUE(logic.fault_latched()) << "pressure back is not enough: latched until reset";

  logic.reset();
  OwnedCommand reset = command("reset");
  state = run_for(logic, milliseconds(100), &reset);
  EXPECT_FALSE(logic.fault_latched());
  EXPECT_TRUE(state.safe_state()) << "reset itself keeps the lock closed and the gripper as it is";
  EXPECT_FALSE(gripper_valve_energised());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);

  state = run_for(logic, milliseconds(300), &grab_again);
  EXPECT_TRUE(gripper_valve_energised()) << "a fresh command acts after the reset";
  EXPECT_FALSE(state.safe_state());
  EXPECT_EQ(state.gripper_confirm(), "connected");
}

TEST_F(RspLogicTest, APressureDropWhileOpenClosesTheLockAndAResetWithoutPressureLatchesAgain) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  fake_->pressure_supply("main_air")->drop();
  hub_msgs::RspState state = run_for(logic, milliseconds(100), &unlock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_EQ(state.lock(), "closing") << "no air: the lock cannot move until pressure returns";
  EXPECT_FALSE(state.unlock_allowed());
  EXPECT_EQ(state.unlock_blocked(), "a pressure failure is latched; reset first");
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault);
  logic.reset();
  OwnedCommand reset = command("reset");
  cycle(logic, &reset);
  EXPECT_TRUE(logic.fault_latched()) << "the pressure is still gone";
  fake_->pressure_supply("main_air")->restore();
  // The stroke starts over once the switch shows pressure again (after its 50 ms debounce).
  state = run_for(logic, milliseconds(240), &reset);
  EXPECT_EQ(state.lock(), "closing");
  state = run_for(logic, milliseconds(20), &reset);
  EXPECT_EQ(state.lock(), "closed");
}

TEST_F(RspLogicTest, AnUnreadablePressureSwitchIsAPressureFailure) {
  auto wiring = fake_->wiring("rsp.pressure_ok");
  ASSERT_TRUE(wiring.is_ok());
  RspLogic logic = make_logic();
  hub_msgs::RspState state = run_for(logic, milliseconds(100), nullptr);  // past the switch's 50 ms debounce
  ASSERT_TRUE(state.pressure_ok());
  EXPECT_TRUE(state.pressure_known());

  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, true).is_ok());
  clock_.advance(kCycle);
  state = cycle(logic, nullptr);
  EXPECT_FALSE(state.pressure_known()) << "the read failed: the pressure is unknown this very cycle";
  EXPECT_FALSE(state.pressure_ok()) << "not the last good reading";
  EXPECT_TRUE(errors_.contains("pressure failure: pressure switch rsp.pressure_ok cannot be read"))
      << errors_.at(0);

  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, false).is_ok());
  state = run_for(logic, milliseconds(100), nullptr);
  EXPECT_TRUE(state.pressure_known());
  EXPECT_TRUE(state.pressure_ok()) << "a good read brings the value back (the failure stays latched)";
  EXPECT_TRUE(logic.fault_latched());
}

// --- Safe states -----------------------------------------------------------------------------------

TEST_F(RspLogicTest, NoCommandInForceClosesTheLockAndKeepsTheGripperEitherWay) {
  for (const bool grab : {true, false}) {
    SCOPED_TRACE(grab ? "gripper closed" : "gripper open");
    SetUp();
    RspLogic logic = make_logic();
    dock_reports(true, true, true);
    OwnedCommand unlock = command("unlock", grab ? "grab" : "release");
    run_for(logic, milliseconds(300), &unlock);
    ASSERT_TRUE(lock_valve_energised());
    ASSERT_EQ(gripper_valve_energised(), grab);
    const hub_msgs::RspState state = cycle(logic, nullptr);  // the watchdog tripped
    EXPECT_FALSE(lock_valve_energised());
    EXPECT_EQ(gripper_valve_energised(), grab);
    EXPECT_TRUE(state.safe_state());
  }
}

TEST_F(RspLogicTest, AResetCommandClosesTheLockAndKeepsTheGripper) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock", "release");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  OwnedCommand reset = command("reset", "grab");
  const hub_msgs::RspState state = cycle(logic, &reset);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_FALSE(gripper_valve_energised()) << "a reset moves nothing but the lock, whatever its gripper says";
  EXPECT_TRUE(state.safe_state());
}

TEST_F(RspLogicTest, EnterSafeStateClosesTheLockAndLeavesTheGripper) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock", "release");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  logic.enter_safe_state();
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_FALSE(gripper_valve_energised());
  EXPECT_TRUE(logic.in_safe_state());
}

// --- Devices that fail -----------------------------------------------------------------------------

TEST_F(RspLogicTest, AMissingChipIsReportedEverythingStaysLockedAndItRecovers) {
  auto wiring = fake_->wiring("rsp.lock_valve");
  ASSERT_TRUE(wiring.is_ok());
  wiring.value().chip->vanish();
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  hub_msgs::RspState state = cycle(logic, &unlock);
  EXPECT_EQ(state.tool(), "undefined");
  EXPECT_FALSE(state.unlock_allowed());
  EXPECT_FALSE(state.pressure_ok());
  EXPECT_FALSE(state.pressure_known()) << "the chip is gone";
  EXPECT_TRUE(errors_.contains("output rsp.lock_valve not available:")) << errors_.at(0);
  EXPECT_TRUE(errors_.contains("input rsp.tool_id.smart_tool not available:"));
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault)
      << "the unreadable pressure switch latched a pressure failure: it outranks the missing devices";

  wiring.value().chip->reappear();
  clock_.advance(std::chrono::seconds(3));  // past the retry interval
  run_for(logic, milliseconds(100), &unlock);
  EXPECT_FALSE(lock_valve_energised()) << "the pressure failure seen meanwhile is latched";
  logic.reset();
  OwnedCommand reset = command("reset");
  run_for(logic, milliseconds(100), &reset);
  state = run_for(logic, milliseconds(100), &unlock);
  EXPECT_TRUE(lock_valve_energised());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
}

TEST_F(RspLogicTest, AFailedWriteIsReported) {
  RspLogic logic = make_logic();
  auto wiring = fake_->wiring("rsp.gripper_valve");
  ASSERT_TRUE(wiring.is_ok());
  ASSERT_TRUE(wiring.value().chip->fail_writes(wiring.value().line, true).is_ok());
  OwnedCommand release = command("lock", "release");
  cycle(logic, &release);
  EXPECT_TRUE(errors_.contains("output rsp.gripper_valve failed to write: i/o error")) << errors_.at(0);
}

TEST_F(RspLogicTest, ABoardThatWouldOpenTheLockOnFaultsIsRefused) {
  for (hal::BoardOutput& output : board_.outputs) {
    if (output.config.signal == "rsp.lock_valve") output.config.safe = true;
  }
  auto logic = testing::make_rsp_logic(settings_, board_, *fake_, dock_.input(), clock_.now().mono);
  ASSERT_FALSE(logic);
  EXPECT_NE(
      logic.error().message.find("drives the lock valve 'rsp.lock_valve' active (= changer open) on faults"),
      std::string::npos)
      << logic.error().message;
}

}  // namespace
}  // namespace hubrt::rsp_ecu
