#include "hubrt/hal/fake/pneumatic_valve.h"

#include <gmock/gmock.h>

#include "hubrt/hal/fake/pressure_supply.h"

#include "sim_test_support.h"

namespace hubrt::hal::fake {
namespace {

using std::chrono::milliseconds;
using std::chrono::nanoseconds;
using ::testing::ElementsAre;

constexpr unsigned kSolenoid = 0;
constexpr unsigned kConfirmA = 1;
constexpr unsigned kConfirmB = 2;
constexpr unsigned kPressureSwitch = 3;
constexpr Duration kActuation = milliseconds(150);

class PneumaticValveTest : public SimTest {
 protected:
  PneumaticValveTest()
      : supply_(gpio_.add_simulator(std::make_unique<PressureSupply>(gpio_, line(kPressureSwitch), true))),
        valve_(gpio_.add_simulator(std::make_unique<PneumaticValve>(
            gpio_, "rsp.gripper_valve", line(kSolenoid),
            std::vector<SimLine>{line(kConfirmA), line(kConfirmB)}, &supply_, kActuation))),
        solenoid_(output(kSolenoid)),
        confirm_a_(input(kConfirmA)),
        confirm_b_(input(kConfirmB)) {}

  void command(bool energised) { ASSERT_TRUE(solenoid_->write(energised).is_ok()); }
  bool confirmed() {
    const bool a = read(*confirm_a_);
    const bool b = read(*confirm_b_);
    EXPECT_EQ(a, b) << "the confirm sensors disagree";
    return a && b;
  }

  PressureSupply& supply_;
  PneumaticValve& valve_;
  std::unique_ptr<DigitalOutput> solenoid_;
  std::unique_ptr<DigitalInput> confirm_a_;
  std::unique_ptr<DigitalInput> confirm_b_;
};

TEST_F(PneumaticValveTest, ConfirmsChangeExactlyAtTheActuationDelay) {
  EXPECT_FALSE(confirmed());
  const Time t0 = now();
  command(true);
  clock_.advance(kActuation - nanoseconds(1));
  EXPECT_FALSE(confirmed());
  EXPECT_TRUE(valve_.arrival().has_value());
  clock_.advance(nanoseconds(1));
  EXPECT_TRUE(confirmed());
  EXPECT_TRUE(valve_.in_energised_position());
  EXPECT_FALSE(valve_.arrival().has_value());
  EXPECT_THAT(chip_.history(kConfirmA), ElementsAre(LevelChange{t0 + kActuation, true}));
}

TEST_F(PneumaticValveTest, ReleaseTakesTheActuationDelayToo) {
  command(true);
  clock_.advance(kActuation);
  ASSERT_TRUE(confirmed());
  command(false);
  clock_.advance(kActuation - nanoseconds(1));
  EXPECT_TRUE(confirmed());
  clock_.advance(nanoseconds(1));
  EXPECT_FALSE(confirmed());
}

TEST_F(PneumaticValveTest, ArrivalIsStampedAtItsOwnTimeWhenNobodyLookedInBetween) {
  const Time t0 = now();
  command(true);
  clock_.advance(std::chrono::seconds(5));
  EXPECT_THAT(chip_.history(kConfirmB), ElementsAre(LevelChange{t0 + kActuation, true}));
}

TEST_F(PneumaticValveTest, DoesNotMoveWithoutPressureAndStrokesInFullWhenItReturns) {
  supply_.drop();
  command(true);
  clock_.advance(std::chrono::seconds(1));
  EXPECT_FALSE(confirmed());
  const Time restored = now();
  supply_.restore();
  clock_.advance(kActuation - nanoseconds(1));
  EXPECT_FALSE(confirmed());
  clock_.advance(nanoseconds(1));
  EXPECT_TRUE(confirmed());
  EXPECT_THAT(chip_.history(kConfirmA), ElementsAre(LevelChange{restored + kActuation, true}));
}

TEST_F(PneumaticValveTest, PressureLostMidStrokeCancelsTheStroke) {
  command(true);
  clock_.advance(milliseconds(100));
  supply_.drop();
  clock_.advance(milliseconds(100));  // past the original arrival
  EXPECT_FALSE(confirmed());
  supply_.restore();
  clock_.advance(milliseconds(149));
  EXPECT_FALSE(confirmed());
  clock_.advance(milliseconds(1));
  EXPECT_TRUE(confirmed());
}

TEST_F(PneumaticValveTest, PressureLossAfterArrivalChangesNothing) {
  command(true);
  clock_.advance(kActuation);
  supply_.drop();
  clock_.advance(std::chrono::seconds(1));
  EXPECT_TRUE(confirmed());
}

TEST_F(PneumaticValveTest, ReversedCommandCancelsTheStroke) {
  command(true);
  clock_.advance(milliseconds(100));
  command(false);
  clock_.advance(std::chrono::seconds(1));
  EXPECT_FALSE(confirmed());
  EXPECT_TRUE(chip_.history(kConfirmA).empty());
}

TEST_F(PneumaticValveTest, StuckValveNeverMovesUntilFreed) {
  valve_.stick(true);
  command(true);
  clock_.advance(std::chrono::seconds(1));
  EXPECT_FALSE(confirmed());
  valve_.stick(false);
  clock_.advance(kActuation - nanoseconds(1));
  EXPECT_FALSE(confirmed());
  clock_.advance(nanoseconds(1));
  EXPECT_TRUE(confirmed());
}

TEST_F(PneumaticValveTest, FailedConfirmSensorDisagreesWithTheOther) {
  valve_.fail_confirm(1, false);
  command(true);
  clock_.advance(kActuation);
  EXPECT_TRUE(read(*confirm_a_));
  EXPECT_FALSE(read(*confirm_b_));
  valve_.repair_confirm(1);
  EXPECT_TRUE(read(*confirm_b_));
}

TEST_F(PneumaticValveTest, SensorFailedActiveShowsConfirmedWhileTheValveIsOpen) {
  valve_.fail_confirm(0, true);
  EXPECT_TRUE(read(*confirm_a_));
  EXPECT_FALSE(read(*confirm_b_));
}

TEST(PneumaticValveWiring, ActiveLowSolenoidIsEnergisedByALowLine) {
  ManualClock clock;
  FakeGpio gpio(clock);
  FakeGpioChip& chip = gpio.add_chip("sim", 4);
  ASSERT_TRUE(chip.drive(0, true, clock.now().mono).is_ok());  // released, pulled up: inactive
  auto& valve = gpio.add_simulator(std::make_unique<PneumaticValve>(
      gpio, "rsp.lock_valve", SimLine(chip, 0, Polarity::kActiveLow),
      std::vector<SimLine>{SimLine(chip, 1, Polarity::kActiveLow)}, nullptr, milliseconds(80)));
  EXPECT_FALSE(valve.in_energised_position());
  EXPECT_TRUE(chip.level(1).value());  // confirm inactive = high on an active-low line
  DigitalOutputConfig config;
  config.signal = "rsp.lock_valve";
  config.chip = "sim";
  config.line = 0;
  config.polarity = Polarity::kActiveLow;
  auto solenoid = std::move(*gpio.open_output(config));
  ASSERT_TRUE(solenoid->write(true).is_ok());
  clock.advance(milliseconds(80));
  EXPECT_TRUE(valve.in_energised_position());
  EXPECT_FALSE(chip.level(1).value());
}

}  // namespace
}  // namespace hubrt::hal::fake
