#include "hubrt/hal/fake/dock_presence_sensor.h"

#include <gmock/gmock.h>

#include "hubrt/hal/common/debounced_input.h"

#include "sim_test_support.h"

namespace hubrt::hal::fake {
namespace {

using std::chrono::milliseconds;
using ::testing::ElementsAre;

constexpr unsigned kSensor = 7;

class DockPresenceSensorTest : public SimTest {};

TEST_F(DockPresenceSensorTest, EachChangeBouncesForTheConfiguredTime) {
  auto& sensor = gpio_.add_simulator(std::make_unique<DockPresenceSensor>(
      gpio_, line(kSensor), milliseconds(20), /*occupied_initially=*/false));
  const Time t0 = now();
  sensor.set_occupied(true);
  EXPECT_TRUE(sensor.bouncing());
  clock_.advance(milliseconds(20));
  EXPECT_FALSE(sensor.bouncing());
  EXPECT_THAT(chip_.history(kSensor),
              ElementsAre(LevelChange{t0, true}, LevelChange{t0 + milliseconds(5), false},
                          LevelChange{t0 + milliseconds(10), true}, LevelChange{t0 + milliseconds(15), false},
                          LevelChange{t0 + milliseconds(20), true}));
}

TEST_F(DockPresenceSensorTest, RawReadsSeeTheBounceAndDebouncedReadsDoNot) {
  auto& sensor = gpio_.add_simulator(
      std::make_unique<DockPresenceSensor>(gpio_, line(kSensor), milliseconds(20), false));
  DigitalInputConfig config;
  config.signal = "dock.slot.smart_tool";
  config.chip = "sim";
  config.line = kSensor;
  // The raw level is sampled from the chip: the line itself is held by the debounced input.
  DebouncedInput debounced(std::move(*gpio_.open_input(config)), milliseconds(30));
  EXPECT_FALSE(debounced.read(now()).value());
  sensor.set_occupied(true);
  int raw_changes = 0;
  bool last_raw = false;
  bool reported = false;
  Time reported_at{};
  for (int ms = 0; ms <= 60; ++ms) {
    const bool level = chip_.level(kSensor).value();
    if (level != last_raw) ++raw_changes;
    last_raw = level;
    const bool now_reported = debounced.read(now()).value();
    if (now_reported && !reported) reported_at = now();
    EXPECT_FALSE(reported && !now_reported) << "debounced level fell back at +" << ms << " ms";
    reported = now_reported;
    clock_.advance(milliseconds(1));
  }
  EXPECT_GE(raw_changes, 5);  // sampled every ms, all five edges of the bounce show
  EXPECT_TRUE(reported);
  // Settled at +20 ms, held 30 ms: reported at +50 ms (the first sample of the final level is +20).
  EXPECT_EQ(reported_at - (now() - milliseconds(61)), milliseconds(50));
}

TEST_F(DockPresenceSensorTest, ZeroBounceGivesOneCleanEdge) {
  auto& sensor =
      gpio_.add_simulator(std::make_unique<DockPresenceSensor>(gpio_, line(kSensor), Duration::zero(), true));
  const Time t0 = now();
  sensor.set_occupied(false);
  EXPECT_FALSE(sensor.bouncing());
  clock_.advance(milliseconds(100));
  EXPECT_THAT(chip_.history(kSensor), ElementsAre(LevelChange{t0, true}, LevelChange{t0, false}));
}

TEST_F(DockPresenceSensorTest, ChangeDuringABounceCancelsTheRestOfIt) {
  auto& sensor = gpio_.add_simulator(
      std::make_unique<DockPresenceSensor>(gpio_, line(kSensor), milliseconds(20), false));
  sensor.set_occupied(true);
  clock_.advance(milliseconds(7));  // edges at +0 and +5 happened
  sensor.set_occupied(false);       // taken again at +7: a fresh bounce towards "empty"
  clock_.advance(milliseconds(100));
  EXPECT_FALSE(chip_.level(kSensor).value());
  const auto history = chip_.history(kSensor);
  ASSERT_FALSE(history.empty());
  EXPECT_EQ(history.back().at, now() - milliseconds(100) + milliseconds(20));
}

TEST_F(DockPresenceSensorTest, ActiveLowSensorIsLowWhileOccupied) {
  gpio_.add_simulator(std::make_unique<DockPresenceSensor>(gpio_, line(kSensor, Polarity::kActiveLow),
                                                           Duration::zero(), true));
  auto in = input(kSensor, Polarity::kActiveLow);
  EXPECT_FALSE(chip_.level(kSensor).value());
  EXPECT_TRUE(read(*in));
}

}  // namespace
}  // namespace hubrt::hal::fake
