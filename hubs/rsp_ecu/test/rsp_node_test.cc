// The tool-changer logic inside the generic Node, as hubd runs it: commands arrive, are validated
// (common fields by the Node, gripper and the unlock interlock by the logic), rejected with a
// reason in error_list, watched by the command watchdog; a reset and a fresh command recover.
#include <gtest/gtest.h>
#include <spdlog/sinks/null_sink.h>
#include <spdlog/spdlog.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/hub_api/node_wiring.h"
#include "hubrt/runtime/node.h"

#include "rsp_logic.h"
#include "rsp_test_support.h"

namespace hubrt::rsp_ecu {
namespace {

using std::chrono::milliseconds;
using testing::command;
using testing::dock_slots;
using testing::DockFeed;
using testing::NullSink;
using testing::OwnedCommand;
using testing::QueueSource;

class RspNodeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/rsp_ecu/rsp_ecu.yaml");
    ASSERT_TRUE(config) << config.error().message;
    auto settings = parse_rsp_settings(config->nodes.at(0));
    ASSERT_TRUE(settings) << settings.error().message;
    auto fake = hal::fake::FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
    auto logic = testing::make_rsp_logic(*settings, board_, *fake_, dock_.input(), clock_.now().mono);
    ASSERT_TRUE(logic) << logic.error().message;
    runtime::NodeOptions options;
    options.name = "rsp";
    options.command_timeout = milliseconds(1000);
    options.log = std::make_shared<spdlog::logger>("rsp", std::make_shared<spdlog::sinks::null_sink_mt>());
    node_ = std::make_unique<runtime::Node<RspLogic>>(options, std::move(*logic), source_, sink_,
                                                      hub_api::message_ops<hub_msgs::RspCommand::Wire>());
  }

  // One cycle: the dock's State (if it is alive) arrives, then `c` (if given), then the node steps.
  const hub_msgs::RspState& step(const OwnedCommand* c = nullptr) {
    if (dock_alive_) dock_.arrive(dock_slots(true, true, smart_tool_home_), clock_.now().mono);
    if (c != nullptr) source_.push(*c);
    node_->step(clock_.now());
    return node_->state();
  }
  // The planner repeats `c` every 100 ms for `span`.
  const hub_msgs::RspState& repeat(const OwnedCommand& c, Duration span) {
    step(&c);
    for (Duration t = milliseconds(100); t <= span; t += milliseconds(100)) {
      clock_.advance(milliseconds(100));
      step(&c);
    }
    return node_->state();
  }
  bool lock_valve_energised() { return fake_->active("rsp.lock_valve").value_or(true); }
  bool gripper_valve_energised() { return fake_->active("rsp.gripper_valve").value_or(false); }
  const runtime::ErrorList& errors() { return node_->errors(); }

  ManualClock clock_;
  hal::BoardConfig board_;
  std::unique_ptr<hal::fake::FakeBackend> fake_;
  DockFeed dock_{milliseconds(500)};
  bool dock_alive_ = true;
  bool smart_tool_home_ = true;
  QueueSource source_;
  NullSink sink_;
  std::unique_ptr<runtime::Node<RspLogic>> node_;
};

TEST_F(RspNodeTest, AnAllowedUnlockTakesEffectAndIsEchoed) {
  step();
  OwnedCommand unlock = command("unlock", "keep");
  const hub_msgs::RspState& state = repeat(unlock, milliseconds(300));
  EXPECT_TRUE(lock_valve_energised());
  EXPECT_EQ(state.echo().action(), "unlock");
  EXPECT_EQ(state.echo().gripper(), "keep");
  EXPECT_TRUE(state.fresh_msg());
  EXPECT_EQ(state.lock(), "open");
  EXPECT_TRUE(errors().empty()) << errors().at(0);
}

TEST_F(RspNodeTest, AnUnlockWithoutTheDocksConfirmationIsRejectedWithItsReason) {
  smart_tool_home_ = false;
  step();
  OwnedCommand lock = command("lock", "grab");
  repeat(lock, milliseconds(200));
  OwnedCommand unlock = command("unlock", "grab");
  const hub_msgs::RspState& state = repeat(unlock, milliseconds(500));
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_EQ(state.echo().action(), "lock") << "the rejected command is not echoed; the one in force stays";
  EXPECT_TRUE(state.locked());
  ASSERT_FALSE(errors().empty());
  EXPECT_EQ(errors().at(0),
            "rejected command: unlock refused: the Dock ECU does not report smart_tool home (slot "
            "'smart_tool' empty); lock kept closed");
  EXPECT_GE(node_->rejected(), 6u);

  smart_tool_home_ = true;  // the robot put the tool in its slot
  step();
  repeat(unlock, milliseconds(100));
  EXPECT_TRUE(lock_valve_energised());
  EXPECT_EQ(node_->state().echo().action(), "unlock");
}

TEST_F(RspNodeTest, UnlockIsRejectedWhenTheDockStateIsStaleOrWasNeverReceived) {
  dock_alive_ = false;
  step();
  OwnedCommand unlock = command("unlock");
  repeat(unlock, milliseconds(300));
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors().contains("no Dock ECU State received yet"));

  dock_alive_ = true;
  step();
  dock_alive_ = false;
  clock_.advance(milliseconds(600));
  repeat(unlock, milliseconds(200));
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors().contains(
      "unlock refused: cannot confirm smart_tool is home: Dock ECU State older than 0.50 s"))
      << errors().at(0);
}

TEST_F(RspNodeTest, BadCommandsAreRejectedAndNothingMoves) {
  step();
  OwnedCommand lock = command("lock", "release");
  repeat(lock, milliseconds(200));
  ASSERT_FALSE(gripper_valve_energised());

  OwnedCommand unknown_action = command("open", "grab");
  OwnedCommand bad_gripper = command("lock", "squeeze");
  OwnedCommand wrong_type = command("lock", "grab");
  wrong_type.set_target_type("dock");
  // Over the IDL bound (string<64>) a command never arrives (Cyclone drops it); built here, the
  // setter cuts it at 64 bytes, which is still no gripper state.
  OwnedCommand too_long = command("lock", std::string(100, 'g'));
  const struct {
    OwnedCommand* command;
    std::string_view reason;
  } cases[] = {
      {&unknown_action, "rejected command: unknown action 'open' (expected one of: lock, unlock, reset)"},
      {&bad_gripper,
       "rejected command: unknown gripper state 'squeeze' (expected grab, release, keep, or empty for keep)"},
      {&wrong_type, "rejected command: wrong target type 'dock' for node 'rsp' of type 'tool_changer'"},
      {&too_long, "rejected command: unknown gripper state 'gggg"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.reason);
    clock_.advance(milliseconds(100));
    const hub_msgs::RspState& state = step(c.command);
    EXPECT_FALSE(gripper_valve_energised()) << "nothing actuated";
    EXPECT_FALSE(lock_valve_energised());
    EXPECT_EQ(state.echo().gripper(), "release");
    ASSERT_FALSE(errors().empty());
    EXPECT_EQ(errors().at(0).substr(0, std::string_view(c.reason).size()), c.reason);
  }

  // A command for another node on the shared topic is not ours: ignored, not rejected.
  const std::uint64_t rejected = node_->rejected();
  OwnedCommand other = command("lock", "grab");
  other.set_target_name("rsp2");
  clock_.advance(milliseconds(100));
  step(&other);
  EXPECT_EQ(node_->rejected(), rejected);
  EXPECT_FALSE(gripper_valve_energised());
}

TEST_F(RspNodeTest, ThePlannerGoingSilentClosesTheLockKeepsTheGripperAndAFreshCommandRecovers) {
  step();
  OwnedCommand unlock = command("unlock", "release");
  repeat(unlock, milliseconds(300));
  ASSERT_TRUE(lock_valve_energised());
  for (int i = 0; i < 11; ++i) {
    clock_.advance(milliseconds(100));
    step();
  }
  const hub_msgs::RspState& state = node_->state();
  EXPECT_FALSE(state.fresh_msg());
  EXPECT_TRUE(state.safe_state());
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_FALSE(gripper_valve_energised()) << "gripper as it is";
  EXPECT_TRUE(errors().contains("command timeout"));

  repeat(unlock, milliseconds(100));
  EXPECT_TRUE(node_->state().fresh_msg());
  EXPECT_TRUE(lock_valve_energised());
}

TEST_F(RspNodeTest, APressureFaultRecoversAfterResetAndAFreshCommand) {
  step();
  OwnedCommand unlock = command("unlock", "grab");
  repeat(unlock, milliseconds(300));
  ASSERT_TRUE(lock_valve_energised());
  fake_->pressure_supply("main_air")->drop();
  repeat(unlock, milliseconds(200));
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors().contains("pressure failure: supply pressure lost"));
  EXPECT_TRUE(node_->state().safe_state());
  fake_->pressure_supply("main_air")->restore();
  repeat(unlock, milliseconds(300));
  EXPECT_FALSE(lock_valve_energised()) << "latched until reset";

  OwnedCommand reset = command("reset");
  const hub_msgs::RspState& state = repeat(reset, milliseconds(200));
  EXPECT_TRUE(state.got_reset());
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors().empty()) << errors().at(0);
  repeat(unlock, milliseconds(300));
  EXPECT_TRUE(lock_valve_energised()) << "the fresh command after the reset acts";
  EXPECT_FALSE(node_->state().got_reset());
}

TEST_F(RspNodeTest, HubStopPutsTheNodeInItsSafeState) {
  step();
  OwnedCommand unlock = command("unlock", "release");
  repeat(unlock, milliseconds(300));
  ASSERT_TRUE(lock_valve_energised());
  node_->enter_safe_state();
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_FALSE(gripper_valve_energised());
}

}  // namespace
}  // namespace hubrt::rsp_ecu
