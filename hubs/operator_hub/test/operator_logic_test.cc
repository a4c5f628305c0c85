// The operator panel's logic under a manual clock on the fake backend, with the hub's test board
// (boards/host-sim-operator-hub.yaml), default configuration and test allow-list: safe without a command,
// verification by badge, rejections with their reason, confirm presses with their sequence number
// (button and screen), logout and reset, a reader unplugged and back, no badge in clear, and a
// cycle that allocates nothing.
#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"
#include "hubrt/hubs/board_devices.h"
#include "hubrt/msgs/type_info.h"

#include "alloc_counter.h"
#include "operator_panel_logic.h"
#include "operator_settings.h"

namespace hubrt::operator_hub {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

const std::string kDir = HUBRT_OPERATOR_HUB_DIR;
constexpr std::string_view kAnnaBadge = "0004123456";
constexpr std::string_view kAnnaTag = "9ad4c64a";
constexpr std::string_view kReader = "operator_rfid";
constexpr std::string_view kButton = "operator.confirm";

hub_msgs::OperatorPanelCommand command(std::string_view action) {
  hub_msgs::OperatorPanelCommand c;
  c.set_target_type("operator_panel");
  c.set_target_name("panel");
  c.set_action(action);
  return c;
}

class OperatorLogicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = hal::load_board(kDir + "/../../boards/host-sim-operator-hub.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto fake = hal::fake::FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
  }

  // As the hub type builds it, with the test allow-list and, optionally, the screen's topic.
  OperatorPanelLogic make_logic(const ScreenConfirmInput* screen = nullptr) {
    auto list = AllowList::load(kDir + "/test/operators.list");
    EXPECT_TRUE(list) << list.error().message;
    const Time now = clock_.now().mono;
    hal::SupervisedBadgeReader reader(*fake_, board_.find_badge_reader(kReader)->config);
    reader.open_now(now);
    auto button = hubs::open_board_input(board_, *fake_, "panel", kButton, now);
    EXPECT_TRUE(button) << button.error().message;
    OperatorDevices devices{std::move(reader), std::move(*button)};
    auto logic = OperatorPanelLogic::create(std::move(*list), std::move(devices), screen, now);
    EXPECT_TRUE(logic) << logic.error().message;
    return std::move(*logic);
  }

  // One cycle as runtime::Node runs it; `in_force` nullptr: not operational.
  hub_msgs::OperatorPanelState cycle(OperatorPanelLogic& logic,
                                     const hub_msgs::OperatorPanelCommand* in_force) {
    const Time now = clock_.now().mono;
    logic.read_inputs(now);
    std::optional<hub_msgs::OperatorPanelCommandView> view;
    if (in_force != nullptr) view = in_force->view();
    logic.update(view ? &*view : nullptr, now);
    errors_.clear();
    hub_msgs::OperatorPanelState state;
    logic.report(state, errors_, now);
    return state;
  }

  void show(std::string_view badge) { fake_->badge_reader(kReader)->present(badge); }
  // Presses and releases the button, each level held past the 20 ms debounce (the debouncer
  // samples at each read: a level counts once two reads 20 ms apart saw it).
  void press(OperatorPanelLogic& logic, const hub_msgs::OperatorPanelCommand* in_force) {
    for (bool level : {true, false}) {
      fake_->input(kButton)->set(level);
      cycle(logic, in_force);
      clock_.advance(milliseconds(30));
      cycle(logic, in_force);
    }
  }
  bool error_mentions(std::string_view text) const { return errors_.contains(text); }

  ManualClock clock_;
  hal::BoardConfig board_;
  std::unique_ptr<hal::fake::FakeBackend> fake_;
  runtime::ErrorList errors_;
  const hub_msgs::OperatorPanelCommand verify_ = command("verify");
};

TEST_F(OperatorLogicTest, WithoutACommandNobodyIsVerifiedAndBadgesAreRefused) {
  auto logic = make_logic();
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
  show(kAnnaBadge);
  const auto state = cycle(logic, nullptr);
  EXPECT_TRUE(state.view().reader_open());
  EXPECT_FALSE(state.view().operator_verified());
  EXPECT_EQ(state.view().badge_reads(), 1U);
  EXPECT_EQ(state.view().last_badge(), "rejected");
  EXPECT_EQ(state.view().last_badge_reason(), "not verifying: no verify command in force");
  EXPECT_EQ(state.view().last_badge_tag(), kAnnaTag);
}

TEST_F(OperatorLogicTest, AKnownBadgeVerifiesItsOperator) {
  auto logic = make_logic();
  cycle(logic, &verify_);
  show(kAnnaBadge);
  auto state = cycle(logic, &verify_);
  EXPECT_TRUE(state.view().operator_verified());
  EXPECT_EQ(state.view().operator_name(), "Anna Svensson");
  EXPECT_EQ(state.view().last_badge(), "accepted");
  EXPECT_EQ(state.view().last_badge_reason(), "");
  EXPECT_EQ(state.view().last_badge_tag(), kAnnaTag);
  clock_.advance(seconds(2));
  state = cycle(logic, &verify_);
  EXPECT_FLOAT_EQ(state.view().verified_for(), 2.0F);
  EXPECT_EQ(state.view().badge_reads(), 1U);
}

TEST_F(OperatorLogicTest, AnUnknownBadgeIsRejectedAndLeavesTheOperatorVerified) {
  auto logic = make_logic();
  show(kAnnaBadge);
  cycle(logic, &verify_);
  show("0004123457");
  const auto state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().last_badge(), "rejected");
  EXPECT_EQ(state.view().last_badge_reason(), "unknown badge");
  EXPECT_NE(state.view().last_badge_tag(), kAnnaTag);
  EXPECT_EQ(state.view().last_badge_tag().size(), 8U);
  EXPECT_EQ(state.view().operator_name(), "Anna Svensson");
  EXPECT_EQ(state.view().badge_reads(), 2U);
}

TEST_F(OperatorLogicTest, AnotherKnownBadgeTakesOver) {
  auto logic = make_logic();
  show(kAnnaBadge);
  cycle(logic, &verify_);
  show("A1B2C3D4");
  const auto state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().operator_name(), "Bo Ek");
}

TEST_F(OperatorLogicTest, MalformedBadgesAreRejectedWithTheirReasonAndNoTag) {
  auto logic = make_logic();
  show(
      "0004\x01"
      "123456");
  auto state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().last_badge(), "rejected");
  EXPECT_EQ(state.view().last_badge_reason(), "malformed: not printable ASCII");
  EXPECT_EQ(state.view().last_badge_tag(), "");
  show(std::string(33, '1'));
  state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().last_badge_reason(), "malformed: too long");
  show("\xc3\xa9t\xc3\xa9");
  state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().last_badge_reason(), "malformed: not printable ASCII");
  EXPECT_FALSE(state.view().operator_verified());
  EXPECT_EQ(state.view().badge_reads(), 3U);
}

TEST_F(OperatorLogicTest, NoStringOfTheStateHoldsTheBadge) {
  auto logic = make_logic();
  show(kAnnaBadge);
  auto state = cycle(logic, &verify_);
  show("0004123457");
  state = cycle(logic, &verify_);
  for (std::string_view field :
       {state.view().operator_name(), state.view().last_badge(), state.view().last_badge_tag(),
        state.view().last_badge_reason(), state.view().confirm_source()}) {
    EXPECT_EQ(field.find("000412345"), std::string_view::npos) << field;
  }
  EXPECT_FALSE(errors_.contains("000412345"));
}

TEST_F(OperatorLogicTest, ButtonPressesCountOnlyWhileAnOperatorIsVerified) {
  auto logic = make_logic();
  cycle(logic, &verify_);
  press(logic, &verify_);
  EXPECT_EQ(logic.confirm_seq(), 0U);  // nobody verified
  show(kAnnaBadge);
  cycle(logic, &verify_);
  press(logic, &verify_);
  auto state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().confirm_seq(), 1U);
  EXPECT_EQ(state.view().confirm_source(), "button");
  press(logic, &verify_);
  clock_.advance(milliseconds(500));
  state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().confirm_seq(), 2U);
  EXPECT_FLOAT_EQ(state.view().confirm_age(), 0.53F);
}

TEST_F(OperatorLogicTest, AHeldButtonIsOnePressAndBounceShorterThanTheDebounceNone) {
  auto logic = make_logic();
  show(kAnnaBadge);
  cycle(logic, &verify_);
  fake_->input(kButton)->set(true);
  clock_.advance(milliseconds(5));
  cycle(logic, &verify_);
  fake_->input(kButton)->set(false);  // a 5 ms bounce: no press
  clock_.advance(milliseconds(30));
  cycle(logic, &verify_);
  EXPECT_EQ(logic.confirm_seq(), 0U);
  fake_->input(kButton)->set(true);
  for (int i = 0; i < 10; ++i) {
    clock_.advance(milliseconds(30));
    cycle(logic, &verify_);
  }
  EXPECT_EQ(logic.confirm_seq(), 1U);
}

TEST_F(OperatorLogicTest, LosingTheCommandLogsOutAndDropsPresses) {
  auto logic = make_logic();
  show(kAnnaBadge);
  cycle(logic, &verify_);
  EXPECT_TRUE(logic.operator_verified());
  press(logic, nullptr);
  const auto state = cycle(logic, nullptr);
  EXPECT_FALSE(state.view().operator_verified());
  EXPECT_EQ(state.view().operator_name(), "");
  EXPECT_EQ(state.view().confirm_seq(), 0U);
}

TEST_F(OperatorLogicTest, LogoutLogsOutAndRefusesBadgesWhileInForce) {
  auto logic = make_logic();
  show(kAnnaBadge);
  cycle(logic, &verify_);
  const auto logout = command("logout");
  auto state = cycle(logic, &logout);
  EXPECT_FALSE(state.view().operator_verified());
  show(kAnnaBadge);
  state = cycle(logic, &logout);
  EXPECT_FALSE(state.view().operator_verified());
  EXPECT_EQ(state.view().last_badge_reason(), "logout in force");
  show(kAnnaBadge);
  state = cycle(logic, &verify_);
  EXPECT_TRUE(state.view().operator_verified());
}

TEST_F(OperatorLogicTest, ScreenPressesCountOncePerPressIdWhileVerified) {
  const msgs::TypeInfo& type = msgs::type_info_of<hub_msgs::OperatorConfirm::Wire>();
  ScreenConfirmInput screen("screen", "/operator_hub/operator/screen_confirm", seconds(1), *type.descriptor,
                            0);
  const auto publish = [&](std::uint32_t press_id) {
    hub_msgs::OperatorConfirm confirm;
    confirm.set_source("screen");
    confirm.set_press_id(press_id);
    *static_cast<hub_msgs::OperatorConfirm::Wire*>(screen.sample_data()) = confirm.wire();
    screen.note_arrival(clock_.now().mono);
  };
  publish(7);  // before the hub started: no press for us
  auto logic = make_logic(&screen);
  show(kAnnaBadge);
  cycle(logic, &verify_);
  EXPECT_EQ(logic.confirm_seq(), 0U);
  publish(8);
  auto state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().confirm_seq(), 1U);
  EXPECT_EQ(state.view().confirm_source(), "screen");
  publish(8);  // the same press again (a repeated sample)
  state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().confirm_seq(), 1U);
  const auto logout = command("logout");
  cycle(logic, &logout);
  publish(9);  // nobody verified
  state = cycle(logic, &logout);
  EXPECT_EQ(state.view().confirm_seq(), 1U);
}

TEST_F(OperatorLogicTest, AnUnpluggedReaderIsMissingThenOpenedAgain) {
  auto logic = make_logic();
  show(kAnnaBadge);
  cycle(logic, &verify_);
  fake_->badge_reader(kReader)->unplug();
  cycle(logic, &verify_);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kDevicesMissing);
  auto state = cycle(logic, nullptr);  // the node is not operational while a device is missing
  EXPECT_FALSE(state.view().reader_open());
  EXPECT_FALSE(state.view().operator_verified());
  EXPECT_TRUE(error_mentions("RFID reader operator_rfid not available"));
  fake_->badge_reader(kReader)->plug_in();
  clock_.advance(seconds(3));
  cycle(logic, nullptr);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
  show(kAnnaBadge);
  state = cycle(logic, &verify_);
  EXPECT_TRUE(state.view().operator_verified());
}

TEST_F(OperatorLogicTest, ResetClearsTheLastBadge) {
  auto logic = make_logic();
  show("nobody");
  cycle(logic, &verify_);
  logic.reset();
  const auto state = cycle(logic, &verify_);
  EXPECT_EQ(state.view().last_badge(), "");
  EXPECT_EQ(state.view().last_badge_tag(), "");
  EXPECT_EQ(state.view().badge_reads(), 1U);  // a count since start: never goes back
}

TEST_F(OperatorLogicTest, TheCycleAllocatesNothingEvenWhenABadgeIsVerified) {
  auto logic = make_logic();
  show(kAnnaBadge);
  cycle(logic, &verify_);  // warm up
  hub_msgs::OperatorPanelState state;
  const auto view = verify_.view();
  show("A1B2C3D4");  // queued (the test allocates), read in the scope
  const hubrt::testing::AllocationScope scope;
  for (int i = 0; i < 50; ++i) {
    clock_.advance(milliseconds(100));
    const Time now = clock_.now().mono;
    logic.read_inputs(now);
    logic.update(&view, now);
    errors_.clear();
    logic.report(state, errors_, now);
  }
  EXPECT_EQ(scope.count(), 0U);
  EXPECT_EQ(state.view().operator_name(), "Bo Ek");
}

TEST(OperatorSettingsTest, ErrorsNameTheLine) {
  auto root = config::YamlMap::load_string(
      "hub: operator_hub\nname: operator_hub\nlayout: node_type\nnodes:\n  panel:\n    type: operator_panel\n"
      "    reader: operator_rfid\n    allow_list: ops.list\n    confirm: x\n",
      "hub.yaml");
  ASSERT_TRUE(root) << root.error().message;
  auto config = config::parse_hub_config(*root);
  ASSERT_TRUE(config) << config.error().message;
  auto settings = parse_operator_settings(config->nodes.at(0), config->file);
  ASSERT_FALSE(settings);
  EXPECT_NE(settings.error().message.find("hub.yaml:9"), std::string::npos) << settings.error().message;
}

TEST(OperatorSettingsTest, ARelativeAllowListIsNextToTheHubFile) {
  auto config = config::load_hub_config(kDir + "/operator_hub.yaml");
  ASSERT_TRUE(config) << config.error().message;
  auto settings = parse_operator_settings(config->nodes.at(0), config->file);
  ASSERT_TRUE(settings) << settings.error().message;
  EXPECT_EQ(settings->allow_list, kDir + "/operators.list");
  EXPECT_TRUE(AllowList::load(settings->allow_list));
}

}  // namespace
}  // namespace hubrt::operator_hub
