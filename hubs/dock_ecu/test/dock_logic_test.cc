#include "dock_logic.h"

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"
#include "hubrt/hal/fake/fake_backend.h"

#include "dock_ecu_hub_type.h"

namespace hubrt::dock_ecu {
namespace {

using std::chrono::milliseconds;

std::string slot_name(const hub_msgs::DockState& state, std::size_t i) {
  return std::string(state.slots()[i].name());
}
bool slot_occupied(const hub_msgs::DockState& state, std::size_t i) {
  return state.slots()[i].occupied();
}

class DockLogicTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
    ASSERT_TRUE(board) << board.error().message;
    board_ = std::move(*board);
    auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/dock_ecu/dock_ecu.yaml");
    ASSERT_TRUE(config) << config.error().message;
    config_ = std::move(*config);
    auto fake = hal::fake::FakeBackend::create(board_, clock_);
    ASSERT_TRUE(fake) << fake.error().message;
    fake_ = std::move(*fake);
    auto slots = parse_slots(config_.nodes.at(0));
    ASSERT_TRUE(slots) << slots.error().message;
    slots_ = std::move(*slots);
  }

  DockLogic make_logic() {
    auto sensors = open_slot_sensors(slots_, board_, *fake_, clock_.now().mono);
    EXPECT_TRUE(sensors) << sensors.error().message;
    auto logic = DockLogic::create(slots_, std::move(*sensors));
    EXPECT_TRUE(logic) << logic.error().message;
    return std::move(*logic);
  }

  // One cycle of the logic at the current time; returns the State it reports.
  hub_msgs::DockState cycle(DockLogic& logic) {
    const Time now = clock_.now().mono;
    logic.read_inputs(now);
    logic.update(nullptr, now);
    errors_.clear();
    hub_msgs::DockState state;
    logic.report(state, errors_, now);
    return state;
  }

  ManualClock clock_;
  hal::BoardConfig board_;
  config::HubConfig config_;
  std::unique_ptr<hal::fake::FakeBackend> fake_;
  std::vector<SlotConfig> slots_;
  runtime::ErrorList errors_;
};

TEST_F(DockLogicTest, TheShippedConfigurationHasFourSlotsOnTheBoard) {
  ASSERT_EQ(slots_.size(), 4u);
  EXPECT_EQ(slots_[2].name, "smart_tool");
  EXPECT_EQ(slots_[2].signal, "dock.slot.smart_tool");
  hal::BoardRequirements required;
  required.hub = "dock_ecu";
  add_requirements(slots_, required);
  EXPECT_TRUE(hal::check_requirements(board_, required));
}

TEST_F(DockLogicTest, ReportsEverySlotWithItsName) {
  DockLogic logic = make_logic();
  clock_.advance(milliseconds(100));  // past any start-up bounce and the debounce window
  hub_msgs::DockState state = cycle(logic);
  ASSERT_EQ(state.slots().size(), 4u);
  EXPECT_EQ(slot_name(state, 0), "ladder_frame_tool");
  EXPECT_EQ(slot_name(state, 3), "spare");
  // host-sim.yaml: ladder-frame and filter tools start docked, the robot holds the smart tool.
  EXPECT_TRUE(slot_occupied(state, 0));
  EXPECT_TRUE(slot_occupied(state, 1));
  EXPECT_FALSE(slot_occupied(state, 2));
  EXPECT_TRUE(errors_.empty());
}

TEST_F(DockLogicTest, ADockedToolShowsOnceTheContactSettles) {
  DockLogic logic = make_logic();
  clock_.advance(milliseconds(100));
  cycle(logic);
  hal::fake::DockPresenceSensor* sensor = fake_->dock_sensor("dock.slot.smart_tool");
  ASSERT_NE(sensor, nullptr);
  sensor->set_occupied(true);
  // The contact bounces (15 ms in host-sim.yaml) and the input is debounced (20 ms): not yet.
  clock_.advance(milliseconds(10));
  EXPECT_FALSE(slot_occupied(cycle(logic), 2));
  clock_.advance(milliseconds(100));
  EXPECT_TRUE(slot_occupied(cycle(logic), 2));
  sensor->set_occupied(false);
  clock_.advance(milliseconds(100));
  EXPECT_TRUE(slot_occupied(cycle(logic), 2)) << "one sample of the new level is not enough";
  clock_.advance(milliseconds(100));
  EXPECT_FALSE(slot_occupied(cycle(logic), 2));
}

TEST_F(DockLogicTest, AReadFailureIsLatchedUntilReset) {
  DockLogic logic = make_logic();
  clock_.advance(milliseconds(100));
  cycle(logic);
  auto wiring = fake_->wiring("dock.slot.filter_tool");
  ASSERT_TRUE(wiring.is_ok());
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, true).is_ok());
  hub_msgs::DockState state = cycle(logic);
  EXPECT_FALSE(slot_occupied(state, 1)) << "an unreadable slot never claims a tool is home";
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault) << "latched until a reset";
  ASSERT_EQ(errors_.size(), 1u);
  EXPECT_EQ(errors_.at(0),
            "slot 'filter_tool': sensor dock.slot.filter_tool failed to read 1 time(s) since the last reset "
            "(last: i/o error)");
  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, false).is_ok());
  clock_.advance(milliseconds(100));
  state = cycle(logic);
  EXPECT_TRUE(slot_occupied(state, 1));
  EXPECT_TRUE(errors_.contains("failed to read 1 time(s)")) << "an intermittent fault stays visible";
  logic.reset();
  cycle(logic);
  EXPECT_TRUE(errors_.empty());
}

TEST_F(DockLogicTest, AMissingChipIsReportedAndTheOtherSlotsWork) {
  auto wiring = fake_->wiring("dock.slot.spare");
  ASSERT_TRUE(wiring.is_ok());
  wiring.value().chip->vanish();
  // All dock slots share the chip in host-sim.yaml: every slot reports it, nothing crashes.
  DockLogic logic = make_logic();
  cycle(logic);
  ASSERT_EQ(errors_.size(), 4u);
  EXPECT_NE(errors_.at(3).find("slot 'spare': sensor dock.slot.spare not available: "), std::string::npos)
      << errors_.at(3);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kDevicesMissing);
  wiring.value().chip->reappear();
  clock_.advance(std::chrono::seconds(3));  // past the retry interval
  cycle(logic);
  clock_.advance(milliseconds(100));
  hub_msgs::DockState state = cycle(logic);
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
  EXPECT_TRUE(slot_occupied(state, 0));
}

Expected<std::vector<SlotConfig>> parse_text(const std::string& node_yaml) {
  auto root = config::YamlMap::load_string("hub: dock_ecu\nnodes:\n  dock:\n" + node_yaml, "dock.yaml");
  if (!root) return std::move(root).error();
  auto config = config::parse_hub_config(*root);
  if (!config) return std::move(config).error();
  return parse_slots(config->nodes.at(0));
}

TEST(DockSlots, BadSettingsNameTheLine) {
  EXPECT_EQ(parse_text("    type: dock\n    slots: []\n").error().message,
            "dock.yaml:5:12: nodes.dock.slots: a dock has 1 to 16 slots, got 0");
  EXPECT_EQ(
      parse_text("    type: dock\n    slots:\n      - {name: a, signal: x}\n      - {name: a, signal: y}\n")
          .error()
          .message,
      "dock.yaml:7:16: nodes.dock.slots[1].name: slot 'a' is listed twice");
  EXPECT_EQ(parse_text("    type: dock\n    slots:\n      - {name: a}\n").error().message,
            "dock.yaml:6:9: nodes.dock.slots[0]: missing required key 'signal'");
  EXPECT_EQ(parse_text("    type: dock\n    slot: []\n").error().message,
            "dock.yaml:5:5: nodes.dock.slot: unknown key (expected one of: type, slots)");
}

}  // namespace
}  // namespace hubrt::dock_ecu
