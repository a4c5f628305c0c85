// The lamp's logic under a manual clock on the fake backend, with the hub's own test board
// (test/lamp-sim.yaml) and default configuration (signal_lamp.yaml): what docs/new-hub.md asks of
// every new hub type's logic — safe without a command, following its command, a device that
// vanishes and comes back, a latched fault cleared by reset, settings errors that name the line.
#include "lamp_logic.h"

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/hubs/board_devices.h"

#include "signal_lamp_hub_type.h"

namespace hubrt::signal_lamp {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr std::string_view kSignal = "lamp.light";

hub_msgs::LampCommand command(std::string_view action) {
  hub_msgs::LampCommand c;
  c.set_target_type("lamp");
  c.set_target_name("lamp");
  c.set_action(action);
  return c;
}

class LampLogicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = hal::load_board(std::string(HUBRT_SIGNAL_LAMP_DIR) + "/test/lamp-sim.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto config = config::load_hub_config(std::string(HUBRT_SIGNAL_LAMP_DIR) + "/signal_lamp.yaml");
    ASSERT_TRUE(config) << config.error().message;
    config_ = std::move(*config);
    auto fake = hal::fake::FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
  }

  // As the hub type builds it: the output opened from the board and handed in.
  LampLogic make_logic() {
    auto signal = parse_lamp_signal(config_.nodes.at(0));
    EXPECT_TRUE(signal) << signal.error().message;
    auto output = hubs::open_board_output(board_, *fake_, "lamp 'lamp'", *signal, clock_.now().mono);
    EXPECT_TRUE(output) << output.error().message;
    return LampLogic(std::move(*output));
  }

  // One cycle at the current time, `in_force` as runtime::Node hands it (nullptr: not
  // operational); returns the State the logic reports.
  hub_msgs::LampState cycle(LampLogic& logic, const hub_msgs::LampCommand* in_force) {
    const Time now = clock_.now().mono;
    logic.read_inputs(now);
    std::optional<hub_msgs::LampCommandView> view;
    if (in_force != nullptr) view = in_force->view();
    logic.update(view ? &*view : nullptr, now);
    errors_.clear();
    hub_msgs::LampState state;
    logic.report(state, errors_, now);
    return state;
  }

  // The line's level as the fake chip sees it (polarity applied).
  bool line_active() {
    const Result<bool> active = fake_->active(kSignal);
    EXPECT_TRUE(active.is_ok());
    return active.is_ok() && active.value();
  }

  ManualClock clock_;
  hal::BoardConfig board_;
  config::HubConfig config_;
  std::unique_ptr<hal::fake::FakeBackend> fake_;
  runtime::ErrorList errors_;
};

TEST_F(LampLogicTest, TheDefaultConfigurationUsesTheTestBoardsOutput) {
  auto required = signal_lamp_hub_type().requirements(config_);
  ASSERT_TRUE(required) << required.error().message;
  ASSERT_EQ(required->outputs, std::vector<std::string>{std::string(kSignal)});
  EXPECT_TRUE(hal::check_requirements(board_, *required));
  EXPECT_TRUE(signal_lamp_hub_type().check(config_));
}

TEST_F(LampLogicTest, OutWithoutACommand) {
  LampLogic logic = make_logic();
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
  const hub_msgs::LampState state = cycle(logic, nullptr);
  EXPECT_FALSE(state.lit());
  EXPECT_FALSE(line_active());
  EXPECT_TRUE(errors_.empty());
}

TEST_F(LampLogicTest, OnLightsItOffAndResetPutItOutAndNotOperationalIsOut) {
  LampLogic logic = make_logic();
  const hub_msgs::LampCommand on = command("on");
  const hub_msgs::LampCommand off = command("off");
  const hub_msgs::LampCommand reset = command("reset");
  EXPECT_TRUE(cycle(logic, &on).lit());
  EXPECT_TRUE(line_active());
  EXPECT_FALSE(cycle(logic, &off).lit());
  EXPECT_FALSE(line_active());
  EXPECT_TRUE(cycle(logic, &on).lit());
  EXPECT_FALSE(cycle(logic, &reset).lit());
  EXPECT_FALSE(line_active());
  EXPECT_TRUE(cycle(logic, &on).lit());
  // The watchdog tripped (or a fault): the node hands in no command, and the lamp goes out.
  EXPECT_FALSE(cycle(logic, nullptr).lit());
  EXPECT_FALSE(line_active());
  EXPECT_TRUE(errors_.empty());
}

TEST_F(LampLogicTest, EnterSafeStatePutsItOutAtOnce) {
  LampLogic logic = make_logic();
  const hub_msgs::LampCommand on = command("on");
  cycle(logic, &on);
  ASSERT_TRUE(line_active());
  logic.enter_safe_state();
  EXPECT_FALSE(line_active());
  EXPECT_FALSE(logic.lit());
}

TEST_F(LampLogicTest, AVanishedChipIsReportedAsMissingAndTheLampComesBackWithIt) {
  LampLogic logic = make_logic();
  const hub_msgs::LampCommand on = command("on");
  ASSERT_TRUE(cycle(logic, &on).lit());
  auto wiring = fake_->wiring(kSignal);
  ASSERT_TRUE(wiring.is_ok());
  wiring.value().chip->vanish();

  // The write finds the line gone: the device is dropped, the node needs it (kRecovering).
  clock_.advance(milliseconds(10));
  hub_msgs::LampState state = cycle(logic, &on);
  EXPECT_FALSE(state.lit()) << "a line that is not open drives nothing";
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kDevicesMissing);
  ASSERT_EQ(errors_.size(), 1u);
  EXPECT_TRUE(errors_.contains("lamp output lamp.light not available: ")) << errors_.at(0);
  // Still gone: retries (with back-off) keep failing, nothing crashes, no fault is latched.
  clock_.advance(seconds(1));
  cycle(logic, nullptr);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kDevicesMissing);

  wiring.value().chip->reappear();
  clock_.advance(seconds(3));  // past the longest back-off (2 s)
  // Not operational while recovering: the node hands in no command; the write opens the line.
  state = cycle(logic, nullptr);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
  EXPECT_FALSE(state.lit());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
  // Operational again: the command in force lights it.
  EXPECT_TRUE(cycle(logic, &on).lit());
  EXPECT_TRUE(line_active());
}

TEST_F(LampLogicTest, AFailedWriteIsAFaultUntilReset) {
  LampLogic logic = make_logic();
  const hub_msgs::LampCommand on = command("on");
  auto wiring = fake_->wiring(kSignal);
  ASSERT_TRUE(wiring.is_ok());
  ASSERT_TRUE(wiring.value().chip->fail_writes(wiring.value().line, true).is_ok());
  cycle(logic, &on);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault);
  ASSERT_EQ(errors_.size(), 1u);
  EXPECT_EQ(errors_.at(0),
            "lamp output lamp.light failed to write 1 time(s) since the last reset (last: i/o error)");
  ASSERT_TRUE(wiring.value().chip->fail_writes(wiring.value().line, false).is_ok());
  cycle(logic, nullptr);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault) << "latched: the operator must see it";
  logic.reset();
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
  EXPECT_TRUE(cycle(logic, &on).lit());
  EXPECT_TRUE(errors_.empty());
}

Expected<hal::BoardRequirements> requirements_of(const std::string& nodes_yaml) {
  auto root = config::YamlMap::load_string("hub: signal_lamp\nnodes:\n" + nodes_yaml, "lamp.yaml");
  if (!root) return std::move(root).error();
  auto config = config::parse_hub_config(*root);
  if (!config) return std::move(config).error();
  return signal_lamp_hub_type().requirements(*config);
}

TEST(SignalLampSettings, BadSettingsNameTheLine) {
  EXPECT_EQ(requirements_of("  lamp:\n    type: lamp\n").error().message,
            "lamp.yaml:4:5: nodes.lamp: missing required key 'signal'");
  EXPECT_EQ(requirements_of("  lamp:\n    type: lamp\n    signal: a\n    colour: red\n").error().message,
            "lamp.yaml:6:5: nodes.lamp.colour: unknown key (expected one of: type, signal)");
  EXPECT_EQ(requirements_of("  lamp:\n    type: dock\n    signal: a\n").error().message,
            "lamp.yaml:4:11: nodes.lamp.type: a signal_lamp hub has nodes of type 'lamp' only, not 'dock'");
}

// The hub layout needs no code of the hub type's own: NodeWiring checks that the hub-level
// messages (msg/SignalLamp*.msg) have a field named as the node, of the node's types.
TEST(SignalLampLayouts, TheHubLayoutNeedsTheNodeCalledLikeItsField) {
  const auto check = [](const std::string& node_name) -> Expected<void> {
    auto root = config::YamlMap::load_string(
        "hub: signal_lamp\nlayout: hub\nnodes:\n  " + node_name + ":\n    type: lamp\n    signal: a\n",
        "lamp.yaml");
    if (!root) return std::move(root).error();
    auto config = config::parse_hub_config(*root);
    if (!config) return std::move(config).error();
    return signal_lamp_hub_type().check(*config);
  };
  EXPECT_TRUE(check("lamp"));
  const auto other = check("beacon");
  ASSERT_FALSE(other);
  EXPECT_NE(other.error().message.find("beacon"), std::string::npos) << other.error().message;
}

}  // namespace
}  // namespace hubrt::signal_lamp
